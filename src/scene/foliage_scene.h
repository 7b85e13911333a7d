// The built-in scene of alpha-masked leaf cards (foliage_scene.cpp).
#pragma once

#include "penumbra/scene.h"

namespace penumbra::scene {

// A tree crown and a hedge of leaf cards over ground, their leaf-cluster texture generated in
// code: the light pass must alpha-test casters for the shadows to have the leaves' holes.
Scene makeFoliageScene();

// The leaf-cluster texture: `size` x `size` RGBA8, alpha 255 on leaves and 0 between them.
TextureImage makeLeafTexture(int size);

}  // namespace penumbra::scene
