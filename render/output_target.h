#pragma once
// A framebuffer with one colour renderbuffer: what a frame is resolved into
// before its pixels are read back or shown (the headless renderer's output,
// the export's, each eye of the stereo preview). One copy of the set-up that
// those three kept apart.
//
// GL objects belong to the context that made them: ensure() and release()
// need it current. The owner calls release() while it is (a destructor
// cannot know), and a target released or never made holds nothing.
namespace hs::render {

class OutputTarget {
 public:
  OutputTarget() = default;
  OutputTarget(const OutputTarget&) = delete;
  OutputTarget& operator=(const OutputTarget&) = delete;

  // Makes the buffers, again only when the size or the format changed.
  // `format` is a sized GL colour format (0 = GL_RGBA8).
  void ensure(int width, int height, unsigned format = 0);
  void release();

  unsigned fbo() const { return fbo_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  unsigned fbo_ = 0, color_ = 0, format_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace hs::render
