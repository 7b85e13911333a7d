// penumbra inside a renderer that is not penumbra: this host owns its window, scene, light pass
// and forward shader, and asks penumbra only to filter its depth texture (ShadowFilter::filter)
// and to sample the result (penumbraShadow() in its own fragment shader). Its light and camera
// are penumbra's fitLightView, viewFromWorld and clipFromView, so that `penumbra render` of the
// scene it writes (--write-obj) with the same options shows the same visibility.
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <penumbra/gl/shadow_filter.h>
#include <penumbra/params.h>
#include <penumbra/scene.h>

#include <algorithm>
#include <bit>
#include <fstream>
#include <glm/gtc/type_ptr.hpp>
#include <iostream>
#include <memory>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "host_options.h"
#include "host_scene.h"
#include "state_check.h"

namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path + " (give --glsl-dir)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

GLuint compileProgram(const std::string& vertex, const std::string& fragment) {
  const GLuint program = glCreateProgram();
  for (const auto& [stage, source] :
       {std::pair{GL_VERTEX_SHADER, &vertex}, std::pair{GL_FRAGMENT_SHADER, &fragment}}) {
    const GLuint shader = glCreateShader(stage);
    const char* text = source->c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      glGetShaderInfoLog(shader, sizeof log, nullptr, log);
      throw std::runtime_error(std::string("host shader: ") + log);
    }
    glAttachShader(program, shader);
    glDeleteShader(shader);
  }
  glLinkProgram(program);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("the host's program does not link");
  return program;
}

// The host's light uniforms, in both of its programs.
void setLightUniforms(GLuint program, const penumbra::LightView& light) {
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "lightFromWorld"), 1, GL_FALSE,
                            glm::value_ptr(light.lightFromWorld));
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "clipFromLight"), 1, GL_FALSE,
                            glm::value_ptr(light.clipFromLight));
  glProgramUniform2f(program, glGetUniformLocation(program, "lightRange"), light.nearDistance,
                     light.farDistance);
}

// The light pass. Window depth needs no colour target; the linear variant writes penumbra's
// metric itself, (distance along the light - near) / (far - near), as `penumbra render` does.
constexpr const char* kDepthVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
uniform mat4 lightFromWorld;
uniform mat4 clipFromLight;
out float lightDistance;
void main() {
  vec4 light = lightFromWorld * vec4(position, 1.0);
  lightDistance = -light.z;
  gl_Position = clipFromLight * light;
}
)";
constexpr const char* kDepthFragment = R"(#version 450 core
in float lightDistance;
uniform vec2 lightRange;  // near, far
layout(location = 0) out float linearDepth;
void main() {
  linearDepth = clamp((lightDistance - lightRange.x) / (lightRange.y - lightRange.x), 0.0, 1.0);
}
)";

constexpr const char* kCameraVertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 clipFromWorld;
out vec3 worldPosition;
out vec3 worldNormal;
void main() {
  worldPosition = position;
  worldNormal = normal;
  gl_Position = clipFromWorld * vec4(position, 1.0);
}
)";

// The host's forward shading, after penumbra's preamble and amalgamated GLSL.
constexpr const char* kCameraFragment = R"(
in vec3 worldPosition;
in vec3 worldNormal;
uniform mat4 lightFromWorld;
uniform mat4 clipFromLight;
uniform vec2 lightRange;
uniform bool linearMap;
uniform vec3 towardLight;
layout(location = 0) out vec4 color;
layout(location = 1) out float visibility;
void main() {
  // The host's own light projection: xy over the map, z the depth its map holds there.
  vec4 light = lightFromWorld * vec4(worldPosition, 1.0);
  vec4 clip = clipFromLight * light;
  vec3 shadowCoord = clip.xyz / clip.w * 0.5 + 0.5;
  if (linearMap) shadowCoord.z = (-light.z - lightRange.x) / (lightRange.y - lightRange.x);
  visibility = penumbraShadow(shadowCoord);
  float lambert = max(dot(normalize(worldNormal), towardLight), 0.0);
  color = vec4(vec3(0.8) * (0.2 + 0.8 * lambert * visibility), 1.0);
}
)";

GLuint makeTexture(GLenum format, int width, int height) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, format, width, height);
  return texture;
}

// Little-endian float PFM (scale -1), rows bottom to top: GL's row order already.
void writePfm(const std::string& path, int width, int height, std::span<const float> values) {
  std::ofstream out(path, std::ios::binary);
  out << "Pf\n" << width << ' ' << height << "\n-1.0\n";
  for (float v : values) {
    const auto bits = std::bit_cast<uint32_t>(v);
    const char bytes[4] = {char(bits), char(bits >> 8), char(bits >> 16), char(bits >> 24)};
    out.write(bytes, 4);
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

int run(const Options& o) {
  const HostScene scene = makeHostScene();
  if (!o.writeObj.empty()) writeObj(scene, o.writeObj);

  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // A debug context reports every GL error to the host's callback: --check-state counts them.
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, o.checkState ? GLFW_TRUE : GLFW_FALSE);
  // Declared first, so that penumbra's objects are released while the context still exists.
  const std::unique_ptr<GLFWwindow, void (*)(GLFWwindow*)> window(
      glfwCreateWindow(o.width, o.height, "penumbra embed", nullptr, nullptr), glfwDestroyWindow);
  if (!window) throw std::runtime_error("no OpenGL 4.5 core window");
  glfwMakeContextCurrent(window.get());

  // The scene in one vertex and one index buffer; a third buffer only for --check-state.
  GLuint buffers[3], vao = 0;
  glCreateBuffers(3, buffers);
  glNamedBufferStorage(buffers[0], GLsizeiptr(scene.vertices.size() * sizeof(HostVertex)),
                       scene.vertices.data(), 0);
  glNamedBufferStorage(buffers[1], GLsizeiptr(scene.indices.size() * sizeof(uint32_t)),
                       scene.indices.data(), 0);
  glNamedBufferStorage(buffers[2], 4096, nullptr, 0);
  glCreateVertexArrays(1, &vao);
  glVertexArrayVertexBuffer(vao, 0, buffers[0], 0, sizeof(HostVertex));
  glVertexArrayElementBuffer(vao, buffers[1]);
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(vao, a);
    glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
    glVertexArrayAttribBinding(vao, a, 0);
  }
  const auto drawScene = [&] {
    glBindVertexArray(vao);
    glDrawElements(GL_TRIANGLES, GLsizei(scene.indices.size()), GL_UNSIGNED_INT, nullptr);
  };

  // penumbra's math for the matrices only, so that `penumbra render` sees the same view.
  penumbra::Light light;
  light.kind = penumbra::LightKind::Directional;
  light.direction = o.lightDir;
  const penumbra::Bounds bounds{glm::make_vec3(scene.boundsMin), glm::make_vec3(scene.boundsMax)};
  const penumbra::LightView lightView = penumbra::fitLightView(light, bounds);
  const penumbra::Camera camera{o.cameraPos, o.cameraTarget, o.cameraFov};
  const glm::mat4 clipFromWorld =
      penumbra::clipFromView(camera, float(o.width) / float(o.height), {bounds, bounds}) *
      penumbra::viewFromWorld(camera);

  // The host's light pass: a D32F depth texture, and the linear variant's R32F colour.
  const bool linear = o.depth == "linear";
  const GLuint depth = makeTexture(GL_DEPTH_COMPONENT32F, o.size, o.size);
  const GLuint linearDepth = linear ? makeTexture(GL_R32F, o.size, o.size) : 0;
  GLuint lightTarget = 0;
  glCreateFramebuffers(1, &lightTarget);
  glNamedFramebufferTexture(lightTarget, GL_DEPTH_ATTACHMENT, depth, 0);
  glNamedFramebufferTexture(lightTarget, GL_COLOR_ATTACHMENT0, linearDepth, 0);
  glNamedFramebufferDrawBuffer(lightTarget, linear ? GL_COLOR_ATTACHMENT0 : GL_NONE);
  const GLuint depthProgram = compileProgram(kDepthVertex, kDepthFragment);
  setLightUniforms(depthProgram, lightView);
  glBindFramebuffer(GL_FRAMEBUFFER, lightTarget);
  glViewport(0, 0, o.size, o.size);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  const float far = 1.0f;
  glClearNamedFramebufferfi(lightTarget, GL_DEPTH_STENCIL, 0, far, 0);
  if (linear) glClearNamedFramebufferfv(lightTarget, GL_COLOR, 0, &far);
  glUseProgram(depthProgram);
  drawScene();

  // penumbra filters the host's texture into the technique's map.
  penumbra::gl::FilterSettings settings;
  settings.technique = penumbra::parseTechnique(o.technique);
  for (const std::string& p : o.params) {
    penumbra::applyParamAssignment(std::span(&settings.technique, 1), settings.params, p);
  }
  const int radius = (o.blurTaps - 1) / 2;
  settings.blur = {penumbra::BlurKernel::Box, radius, std::max(0.5f, 0.5f * float(radius))};
  settings.filter = penumbra::parseFilterMode(o.filter);
  penumbra::gl::DepthInput input;
  input.texture = linear ? linearDepth : depth;
  input.size = o.size;
  input.encoding =
      linear ? penumbra::gl::DepthEncoding::LinearDepth : penumbra::gl::DepthEncoding::WindowDepth;
  input.perspective = lightView.perspective;
  input.nearDistance = lightView.nearDistance;
  input.farDistance = lightView.farDistance;
  penumbra::gl::ShadowFilter filter;
  const auto filterMap = [&] { filter.filter(input, settings); };
  if (!o.checkState) {
    filterMap();
  } else if (!callKeepsHostState({depthProgram, vao, lightTarget, input.texture, buffers[2]},
                                 filterMap)) {
    return 1;
  }
  const penumbra::gl::FilterMemory memory = filter.memory();
  std::cout << "penumbra holds " << memory.total() << " bytes on the GPU: channels "
            << memory.channels << ", scratch " << memory.scratch << ", summed-area "
            << memory.summedArea << ", auxiliary " << memory.auxiliary << ", imported depth "
            << memory.importedDepth << ", blocks " << memory.blocks << "\n";

  // The host's forward pass: colour, and the visibility it writes out.
  const GLuint color = makeTexture(GL_RGBA8, o.width, o.height);
  const GLuint visibility = makeTexture(GL_R32F, o.width, o.height);
  const GLuint cameraDepth = makeTexture(GL_DEPTH_COMPONENT32F, o.width, o.height);
  GLuint frame = 0;
  glCreateFramebuffers(1, &frame);
  glNamedFramebufferTexture(frame, GL_COLOR_ATTACHMENT0, color, 0);
  glNamedFramebufferTexture(frame, GL_COLOR_ATTACHMENT1, visibility, 0);
  glNamedFramebufferTexture(frame, GL_DEPTH_ATTACHMENT, cameraDepth, 0);
  const GLenum targets[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(frame, 2, targets);
  const std::string glsl = readText(
      o.glslDir + "/penumbra_" + std::string(penumbra::techniqueId(settings.technique)) + ".glsl");
  const GLuint cameraProgram = compileProgram(
      kCameraVertex, "#version 450 core\n" + filter.shaderPreamble() + glsl + kCameraFragment);
  glProgramUniformMatrix4fv(cameraProgram, glGetUniformLocation(cameraProgram, "clipFromWorld"), 1,
                            GL_FALSE, glm::value_ptr(clipFromWorld));
  setLightUniforms(cameraProgram, lightView);
  glProgramUniform1i(cameraProgram, glGetUniformLocation(cameraProgram, "linearMap"), linear);
  const glm::vec3 towardLight = -glm::normalize(o.lightDir);
  glProgramUniform3fv(cameraProgram, glGetUniformLocation(cameraProgram, "towardLight"), 1,
                      glm::value_ptr(towardLight));
  // Whatever the light pass (or --check-state) left, the forward pass sets what it needs.
  glBindFramebuffer(GL_FRAMEBUFFER, frame);
  glViewport(0, 0, o.width, o.height);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  const float sky[4] = {0.6f, 0.7f, 0.9f, 1.0f}, lit[4] = {1.0f, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(frame, GL_COLOR, 0, sky);
  glClearNamedFramebufferfv(frame, GL_COLOR, 1, lit);  // nothing drawn: lit, as render writes
  glClearNamedFramebufferfi(frame, GL_DEPTH_STENCIL, 0, 1.0f, 0);
  filter.bind();
  glUseProgram(cameraProgram);
  drawScene();

  if (!o.out.empty()) {
    std::vector<float> values(size_t(o.width) * size_t(o.height));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(visibility, 0, GL_RED, GL_FLOAT, GLsizei(values.size() * sizeof(float)),
                      values.data());
    writePfm(o.out, o.width, o.height, values);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  try {
    options = parseOptions(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "penumbra-embed: " << e.what() << "\n" << optionsUsage();
    return 2;
  }
  glfwSetErrorCallback([](int, const char* text) { std::cerr << "GLFW: " << text << "\n"; });
  if (!glfwInit()) return 1;
  int code = 1;
  try {
    code = run(options);
  } catch (const std::exception& e) {  // penumbra::Error and the host's own
    std::cerr << "penumbra-embed: " << e.what() << "\n";
  }
  glfwTerminate();
  return code;
}
