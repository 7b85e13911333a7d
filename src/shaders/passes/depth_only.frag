// Depth-only camera pass (the depth-bounds reduction's input): nothing to write but depth.
void main() {}
