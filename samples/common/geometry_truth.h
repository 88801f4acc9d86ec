// The geometry truth: ambient visibility ray-traced against a scene's triangles (Intel Embree 3), the measure
// of what a viewer of the scene would see, as opposed to REFERENCE, which ray-traces the depth buffer and so
// knows only the surfaces the camera sees (and takes each of them as infinitely thick unless told otherwise).
//
// THE QUANTITY, per pixel of the output rectangle: the surface the camera sees through the pixel's centre
// (the primary hit, the surface the rasteriser puts there), its geometric normal n turned to face the camera,
// and
//     V = 1 - (1/pi) * integral over the hemisphere of n of rho(d(w)) max(0, n.w) dw
// with d(w) the distance from the surface to the nearest triangle along w (misses contribute 0) and rho the
// falloff of the method measured, evaluated by the SDK's own definition (obscura_evaluate_falloff). Sky pixels
// (no primary hit) are 1, as the SDK writes them.
//
// THE ESTIMATOR: cosine-weighted rays, so V = 1 - mean(rho(d)). Ray i of a pixel takes the i-th point of the
// R2 sequence (the 2D rank-1 lattice of the plastic number: every prefix of it is evenly stratified over the
// unit square), shifted by a per-pixel rotation hashed from the pixel and the seed (Cranley-Patterson), mapped
// to the hemisphere by Malley's method. Rays are traced in batches and each pixel adds its rays to its running
// sum one after the other, so the result depends only on the seed and the ray count, never on the thread count
// or the batch sizes (to the bit); a progressive caller traces a few rays at a time and reads the estimate.
//
// Several falloffs are estimated from one set of rays (a hit's distance is weighed by each): a comparison of
// methods with different falloffs costs one trace.
#ifndef OBSCURA_SAMPLES_GEOMETRY_TRUTH_H
#define OBSCURA_SAMPLES_GEOMETRY_TRUTH_H

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "demo_scene.h"
#include "image_io.h"
#include "obscura/obscura.h"

namespace obscura::samples {

// What the camera of a rasterised frame sees, with the frame's pixel layout: the depth texture of
// depth_width x depth_height pixels covers the projection's whole clip space (guard band included), and the
// truth covers output_rect of it.
struct TruthView {
    glm::mat4 view{1.0f};        // world -> view
    glm::mat4 projection{1.0f};  // view -> clip, of the whole depth texture
    int depth_width = 0;
    int depth_height = 0;
    obscura_rect output_rect{};
    float near_plane = 0.1f;     // primary rays start on the near plane and end on the far plane, as the
    float far_plane = 50.0f;     // rasteriser clips (+infinity for an infinite projection)

    // The view of a frame render_scene() rasterised (its view, projection, sizes and output rectangle).
    static TruthView of(const SceneFrame& frame);
};

// The triangles of a mesh in an Embree scene (BVH built once); RAII over the Embree device and scene.
// Thread-safe to trace from any number of threads once built.
class TruthScene {
public:
    // Throws std::invalid_argument for a mesh without triangles, std::runtime_error when Embree fails.
    explicit TruthScene(const SceneMesh& mesh);
    ~TruthScene();
    TruthScene(const TruthScene&) = delete;
    TruthScene& operator=(const TruthScene&) = delete;

    struct Hit {
        float distance = 0.0f;      // along the unit direction
        glm::vec3 normal{0.0f};     // geometric normal of the triangle hit, unit length, not oriented
        uint32_t triangle = 0;
    };
    // Nearest hit of origin + t * direction (unit length) for t in (t_near, t_far); false for none.
    bool intersect(const glm::vec3& origin, const glm::vec3& direction, float t_near, float t_far, Hit* hit) const;

    int triangle_count() const { return triangle_count_; }
    // How far above a surface point p a secondary ray starts: past the float rounding of p, tiny against the
    // scene (a few float steps of |p| plus a millionth of the scene's diagonal).
    float surface_offset(const glm::vec3& p) const;

private:
    struct Embree;
    std::unique_ptr<Embree> embree_;
    int triangle_count_ = 0;
    float extent_ = 0.0f;  // the diagonal of the mesh's bounding box
};

struct GeometryTruthOptions {
    uint32_t seed = 1;  // picks the per-pixel rotations: another seed gives another, equally good, estimate
    int threads = 0;    // worker threads for tracing; 0: every hardware thread
    // When it becomes true the constructor's primary rays stop at a row boundary (a progressive caller that
    // restarts need not wait for them); the object then has cancelled() true and traces nothing.
    const std::atomic<bool>* cancel = nullptr;
};

// The progressive estimate for one view and a list of falloffs.
class GeometryTruth {
public:
    static constexpr uint32_t kSky = 0xffffffffu;

    // Traces the primary rays (one per output pixel) at once. `falloffs`: settings of any method, each
    // weighing hits with that method's falloff (obscura_evaluate_falloff); at least one. The scene must
    // outlive this object. Throws std::invalid_argument for bad settings (naming the status) or an empty view.
    GeometryTruth(const TruthScene& scene, const TruthView& view, std::vector<obscura_settings> falloffs,
                  GeometryTruthOptions options = {});

    // Traces `rays` more rays per pixel (ray indices rays_traced() ... + rays - 1 of each pixel's sequence);
    // false at once when cancelled().
    // When `cancel` becomes true, returns early at a row boundary and keeps the previous estimate (the partial
    // batch is discarded); returns whether the batch completed. An exception of a worker thread (out of memory)
    // is rethrown here, after every thread has joined, with the previous estimate kept.
    bool trace(int rays, const std::atomic<bool>* cancel = nullptr);

    // Whether options.cancel stopped the primary rays: the object holds no usable estimate.
    bool cancelled() const { return cancelled_; }
    int rays_traced() const { return rays_traced_; }
    uint64_t rays_cast() const { return uint64_t(rays_traced_) * uint64_t(geometry_pixels_); }
    int width() const { return width_; }
    int height() const { return height_; }
    size_t falloff_count() const { return falloffs_.size(); }

    // The estimate so far for falloffs[index]: visibility in [0, 1], one channel, rows bottom-up; 1 on sky
    // (everywhere before the first ray).
    FloatImage visibility(size_t index) const;
    // The bent normal for falloffs[index]: the mean of the traced directions, each weighed by its cosine (the rays
    // are cosine-distributed) and by how unoccluded it is, 1 - rho(hit distance) (a miss: 1), normalised; in view
    // space (as obscura_output.bent_normal_texture), three channels, rows bottom-up; (0, 0, 1) on sky, the
    // normal where every ray is fully occluded or before the first ray.
    FloatImage bent_normal(size_t index) const;
    // Positive view depth (distance from the eye plane, metres) of each primary hit; 0 on sky.
    FloatImage view_depth() const;
    // One byte per pixel: 1 where the primary ray hit the scene, 0 on sky (compare_images' mask).
    const std::vector<uint8_t>& geometry_mask() const { return mask_; }
    // The triangle of each primary hit, kSky on sky.
    const std::vector<uint32_t>& primary_triangles() const { return triangles_; }
    size_t geometry_pixels() const { return geometry_pixels_; }

private:
    void trace_row(int y, int first_ray, int rays, std::vector<float>& distances, std::vector<float>& rho,
                   std::vector<glm::vec3>& directions);

    const TruthScene& scene_;
    std::vector<obscura_settings> falloffs_;
    GeometryTruthOptions options_;
    int width_ = 0;
    int height_ = 0;
    int rays_traced_ = 0;
    bool cancelled_ = false;
    size_t geometry_pixels_ = 0;
    std::vector<glm::vec3> position_;  // primary hit, world space
    std::vector<glm::vec3> normal_;    // geometric normal facing the camera
    std::vector<float> view_depth_;
    std::vector<uint8_t> mask_;
    std::vector<uint32_t> triangles_;
    std::vector<glm::vec2> rotation_;  // per-pixel Cranley-Patterson shift
    std::vector<double> sums_;         // per falloff, per pixel: sum of rho over the rays traced
    std::vector<double> batch_;        // the sums with the current batch's rays (committed when it completes)
    std::vector<glm::dvec3> bent_sums_;   // per falloff, per pixel: sum of (1 - rho) * direction (world space)
    std::vector<glm::dvec3> bent_batch_;  // as batch_
    glm::dmat3 world_to_view_{1.0};
};

// Hemisphere direction i of a pixel (unit length, tangent frame: z along the normal) for the rotation
// `shift` in [0, 1)^2: the R2 point i, shifted, mapped by Malley's method (cosine-weighted). Exposed for tests.
glm::vec3 truth_ray_direction(uint32_t i, glm::vec2 shift);

}  // namespace obscura::samples

#endif  // OBSCURA_SAMPLES_GEOMETRY_TRUTH_H
