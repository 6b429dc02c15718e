#pragma once
// Measurement points on the GPU, with a cost per frame that does not grow with stored points:
// - one append-only VBO per robot, grown by doubling with glCopyBufferSubData; each frame uploads
//   only the points added since the last (sync());
// - robots that show every point are rendered into an accumulation texture (an FBO) once, and the
//   texture is drawn each frame; new points are added to it incrementally;
// - while the view moves, the last finished texture is shown re-projected (one textured quad);
//   once the view holds still, a new texture is rendered in steps and swapped in when complete.
//   Each step rasterises as many points as fit the target frame time (PointPacer, fed with the
//   time of earlier frames), so no frame overruns whatever the renderer or the load;
// - points are stored in the map frame (placed through the correction of their arrival), so a
//   new correction adds nothing to redraw;
// - robots limited to their last N points are drawn straight from their VBO (N is bounded).
#include <cstdint>
#include <vector>

#include "common/core/result.hpp"
#include "viewer/core/point_pacer.hpp"
#include "viewer/core/robot_registry.hpp"
#include "viewer/gl/gl_program.hpp"
#include "viewer/gl/gl_viewport.hpp"

namespace slam::viewer {

class PointLayer {
 public:
  PointLayer() = default;
  ~PointLayer();
  PointLayer(const PointLayer&) = delete;
  PointLayer& operator=(const PointLayer&) = delete;

  // `pacing` must be valid (validate(PacerConfig)).
  Status init(const PacerConfig& pacing);
  // Uploads the points each robot gained since the last call.
  void sync(const RobotRegistry& robots);
  // Draws into `px` (the map viewport of `view` in framebuffer pixels).
  void draw(const ViewTransform& view, const PixelRect& px, const RobotRegistry& robots, double fb_scale);
  // The frame ended (after the buffer swap) and took `frame_ms`, not counting a frame-rate cap's
  // sleep: sizes the texture's next steps (PointPacer). Call it every frame, drawn or not.
  void end_frame(double frame_ms);

  struct Stats {
    uint64_t points_drawn = 0;        // rasterised this frame (accumulation + direct)
    uint64_t points_accumulated = 0;  // of those, into the accumulation texture
    bool settled = false;             // the texture shown matches the current view and settings
    size_t gpu_bytes = 0;             // vertex buffers + accumulation textures
    uint64_t step_budget = 0;         // points the texture could take this frame
  };
  const Stats& stats() const { return stats_; }

 private:
  struct RobotBuffer {
    GLuint vbo = 0;
    GLuint vao = 0;
    size_t capacity = 0;  // points
    size_t uploaded = 0;
    uint64_t generation = 0;
  };
  struct Target {
    GLuint fbo = 0;
    GLuint texture = 0;
    int width = 0, height = 0;
    bool valid = false;
    uint64_t epoch = 0;
    ViewTransform view;
    std::vector<float> fingerprint;
    std::vector<size_t> drawn;  // per robot: points already in the texture
  };

  void grow(RobotBuffer& b, size_t points);
  bool current(const Target& t, const ViewTransform& view, const std::vector<float>& fp,
               const PixelRect& px) const;
  void reset(Target& t, const ViewTransform& view, const std::vector<float>& fp, const PixelRect& px);
  // Adds up to stats_.step_budget points to `t`; true once it holds them all.
  bool advance(Target& t, const RobotRegistry& robots, double fb_scale);
  // Draws points [first, first + count) of robot `r`.
  void draw_range(const RobotBuffer& b, const RobotView& r, size_t first, size_t count,
                  const Affine2& world_to_ndc, double fb_scale);
  void show(const Target& t, const Affine2& delta);
  void fingerprint(const RobotRegistry& robots, std::vector<float>& out) const;

  GlProgram points_;
  GlProgram blit_;
  GLuint blit_vao_ = 0;
  PointPacer pacer_{PacerConfig{}};
  uint64_t texture_points_this_frame_ = 0;  // rasterised into a texture since the last end_frame()
  std::vector<RobotBuffer> buffers_;
  Target targets_[2];
  int shown_ = 0;
  uint64_t epoch_ = 1;     // bumped when a robot's points were reset
  uint64_t removals_ = 0;  // RobotRegistry::removals() the buffers were uploaded for
  bool have_last_view_ = false;
  ViewTransform last_view_;
  std::vector<float> fp_scratch_;
  Stats stats_;
};

}  // namespace slam::viewer
