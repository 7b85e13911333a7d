// The scene area's GL texture: the displayed 8-bit sRGB pixels at one texel per window pixel.
#pragma once

#include <epoxy/gl.h>

#include "display_image.h"

namespace penumbra::viewer {

class SceneTexture {
 public:
  SceneTexture() { glCreateTextures(GL_TEXTURE_2D, 1, &id_); }
  ~SceneTexture() { glDeleteTextures(1, &id_); }
  SceneTexture(const SceneTexture&) = delete;
  SceneTexture& operator=(const SceneTexture&) = delete;

  void upload(const DisplayImage& image) {
    if (image.width != width_ || image.height != height_) {
      glDeleteTextures(1, &id_);
      glCreateTextures(GL_TEXTURE_2D, 1, &id_);
      glTextureStorage2D(id_, 1, GL_RGB8, image.width, image.height);
      // Nearest: the texels land on pixels one to one, the window shows the render's bytes.
      glTextureParameteri(id_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      glTextureParameteri(id_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
      width_ = image.width;
      height_ = image.height;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(id_, 0, 0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, image.rgb.data());
  }
  GLuint id() const { return id_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  GLuint id_ = 0;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace penumbra::viewer
