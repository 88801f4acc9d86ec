#include "geometry_truth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <exception>
#include <mutex>
#include <thread>

#include <embree3/rtcore.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "integer_hash.h"

namespace obscura::samples {
namespace {

// The R2 sequence's step: (1/g, 1/g^2) for the plastic number g, the real root of x^3 = x + 1.
constexpr double kR2StepX = 0.75487766624669276005;
constexpr double kR2StepY = 0.56984029099805326591;

// An orthonormal basis around unit n (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
void tangent_frame(const glm::vec3& n, glm::vec3* t, glm::vec3* b) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    *t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

std::string embree_error_text(RTCDevice device) {
    switch (rtcGetDeviceError(device)) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
        default: return "unknown error";
    }
}

// Runs body(row) for rows [0, rows) on `threads` threads (rows handed out one at a time) with a
// per-thread scratch state; stops handing out rows once `cancel` is set. The first exception a worker throws
// stops the others and is rethrown here once every thread has joined.
template <typename Scratch, typename Body>
void parallel_rows(int rows, int threads, const std::atomic<bool>* cancel, Body body) {
    std::atomic<int> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto worker = [&] {
        try {
            Scratch scratch;
            for (;;) {
                if (failed.load(std::memory_order_relaxed)) return;
                if (cancel && cancel->load(std::memory_order_relaxed)) return;
                const int row = next.fetch_add(1);
                if (row >= rows) return;
                body(row, scratch);
            }
        } catch (...) {
            const std::lock_guard<std::mutex> lock(failure_mutex);
            if (!failure) failure = std::current_exception();
            failed = true;
        }
    };
    const int count = std::max(1, std::min(threads, rows));
    std::vector<std::thread> pool;
    try {
        for (int i = 1; i < count; ++i) pool.emplace_back(worker);
    } catch (...) {
        // No more threads to be had: the ones started and this one do the work.
    }
    worker();
    for (std::thread& thread : pool) thread.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace

TruthView TruthView::of(const SceneFrame& frame) {
    TruthView view;
    view.view = frame.view;
    view.projection = glm::make_mat4(frame.projection);
    view.depth_width = frame.depth_width;
    view.depth_height = frame.depth_height;
    view.output_rect = frame.output_rect;
    view.near_plane = frame.near_plane;
    view.far_plane = frame.far_plane;
    return view;
}

// ---- TruthScene -----------------------------------------------------------------------------------

struct TruthScene::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~Embree() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

TruthScene::TruthScene(const SceneMesh& mesh) : embree_(std::make_unique<Embree>()) {
    triangle_count_ = mesh.triangle_count();
    if (triangle_count_ <= 0) throw std::invalid_argument("geometry truth: the mesh has no triangles");
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device) throw std::runtime_error("geometry truth: rtcNewDevice failed (Embree)");
    embree_->scene = rtcNewScene(embree_->device);
    // Robust traversal: rays that graze an edge shared by two triangles must not slip between them.
    rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);

    RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const int vertex_count = mesh.vertex_count();
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                 RTC_FORMAT_FLOAT3, 3 * sizeof(float), size_t(vertex_count)));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                   RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                                   size_t(triangle_count_)));
    if (!vertices || !indices) {
        const std::string error = embree_error_text(embree_->device);
        rtcReleaseGeometry(geometry);
        throw std::runtime_error("geometry truth: Embree could not allocate the mesh's buffers (" + error + ")");
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (int v = 0; v < vertex_count; ++v) {
        for (int k = 0; k < 3; ++k) vertices[3 * v + k] = mesh.vertices[size_t(6 * v + k)];
        const glm::vec3 position(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]);
        lo = glm::min(lo, position);
        hi = glm::max(hi, position);
    }
    const float diagonal = glm::length(hi - lo);
    extent_ = std::isfinite(diagonal) ? diagonal : 0.0f;
    for (int i = 0; i < 3 * triangle_count_; ++i) indices[i] = uint32_t(i);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(embree_->scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(embree_->scene);
    if (rtcGetDeviceError(embree_->device) != RTC_ERROR_NONE) {
        throw std::runtime_error("geometry truth: Embree failed to build the scene (" +
                                 embree_error_text(embree_->device) + ")");
    }
}

TruthScene::~TruthScene() = default;

bool TruthScene::intersect(const glm::vec3& origin, const glm::vec3& direction, float t_near, float t_far,
                           Hit* hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query;
    query.ray.org_x = origin.x;
    query.ray.org_y = origin.y;
    query.ray.org_z = origin.z;
    query.ray.dir_x = direction.x;
    query.ray.dir_y = direction.y;
    query.ray.dir_z = direction.z;
    query.ray.tnear = t_near;
    query.ray.tfar = t_far;
    query.ray.time = 0.0f;
    query.ray.mask = 0xffffffffu;
    query.ray.id = 0;
    query.ray.flags = 0;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->scene, &context, &query);
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    if (hit) {
        hit->distance = query.ray.tfar;
        hit->normal = glm::normalize(glm::vec3(query.hit.Ng_x, query.hit.Ng_y, query.hit.Ng_z));
        hit->triangle = query.hit.primID;
    }
    return true;
}

float TruthScene::surface_offset(const glm::vec3& p) const {
    // 64 float steps at p's magnitude cover the rounding of a primary hit's position (its distance has a
    // relative error of a few steps); a millionth of the scene's size keeps secondary rays off the surface's own
    // triangles where p is near the origin. Both stay far below any contact a falloff can see.
    const float magnitude = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    return 64.0f * std::numeric_limits<float>::epsilon() * magnitude + 1e-6f * extent_;
}

// ---- GeometryTruth --------------------------------------------------------------------------------

glm::vec3 truth_ray_direction(uint32_t i, glm::vec2 shift) {
    // The lattice in double: i * step loses no bits of the fraction for any i below 2^32.
    double u = double(shift.x) + double(i) * kR2StepX;
    double v = double(shift.y) + double(i) * kR2StepY;
    u -= std::floor(u);
    v -= std::floor(v);
    // Malley's method: a uniform point on the unit disc, lifted onto the hemisphere, is cosine-distributed.
    const double radius = std::sqrt(u), phi = 2.0 * glm::pi<double>() * v;
    return glm::vec3(float(radius * std::cos(phi)), float(radius * std::sin(phi)), float(std::sqrt(std::max(0.0, 1.0 - u))));
}

GeometryTruth::GeometryTruth(const TruthScene& scene, const TruthView& view, std::vector<obscura_settings> falloffs,
                             GeometryTruthOptions options)
    : scene_(scene), falloffs_(std::move(falloffs)), options_(options) {
    if (falloffs_.empty()) throw std::invalid_argument("geometry truth: no falloff to estimate");
    for (const obscura_settings& settings : falloffs_) {
        const obscura_status status = obscura_evaluate_falloff(&settings, nullptr, nullptr, 0);
        if (status != OBSCURA_OK) {
            throw std::invalid_argument(std::string("geometry truth: the falloff's settings are refused (") +
                                        obscura_status_string(status) + ")");
        }
    }
    width_ = view.output_rect.width;
    height_ = view.output_rect.height;
    if (width_ <= 0 || height_ <= 0 || view.depth_width <= 0 || view.depth_height <= 0) {
        throw std::invalid_argument("geometry truth: the view has no pixels");
    }
    if (options_.threads <= 0) options_.threads = int(std::max(1u, std::thread::hardware_concurrency()));

    const size_t pixels = size_t(width_) * size_t(height_);
    position_.assign(pixels, glm::vec3(0.0f));
    normal_.assign(pixels, glm::vec3(0.0f));
    view_depth_.assign(pixels, 0.0f);
    mask_.assign(pixels, 0);
    triangles_.assign(pixels, kSky);
    rotation_.resize(pixels);
    sums_.assign(pixels * falloffs_.size(), 0.0);
    batch_.assign(pixels * falloffs_.size(), 0.0);
    bent_sums_.assign(pixels * falloffs_.size(), glm::dvec3(0.0));
    bent_batch_.assign(pixels * falloffs_.size(), glm::dvec3(0.0));
    world_to_view_ = glm::dmat3(glm::dmat4(view.view));

    // Primary rays in view space, in double: through the centre of the pixel's texel of the depth texture,
    // from the near plane to the far plane.
    const glm::dmat4 inverse_projection = glm::inverse(glm::dmat4(view.projection));
    const glm::dmat4 inverse_view = glm::inverse(glm::dmat4(view.view));
    auto ndc_depth = [&](double view_z) {
        const glm::dvec4 clip = glm::dmat4(view.projection) * glm::dvec4(0.0, 0.0, view_z, 1.0);
        return clip.z / clip.w;
    };
    const double near_plane = view.near_plane;
    const double ndc_near = ndc_depth(-near_plane), ndc_mid = ndc_depth(-2.0 * near_plane);
    const double far_plane = std::isfinite(view.far_plane) ? double(view.far_plane) : 1e30;

    parallel_rows<int>(height_, options_.threads, options_.cancel, [&](int y, int&) {
        for (int x = 0; x < width_; ++x) {
            const size_t index = size_t(y) * size_t(width_) + size_t(x);
            const uint32_t seed = hash32(options_.seed * 0x9e3779b9U + uint32_t(index));
            rotation_[index] = glm::vec2(unit_float(hash32(seed ^ 0x68bc21ebU)), unit_float(hash32(seed ^ 0x02e5be93U)));

            const double ndc_x = 2.0 * (view.output_rect.x + x + 0.5) / view.depth_width - 1.0;
            const double ndc_y = 2.0 * (view.output_rect.y + y + 0.5) / view.depth_height - 1.0;
            glm::dvec4 a = inverse_projection * glm::dvec4(ndc_x, ndc_y, ndc_near, 1.0);
            glm::dvec4 b = inverse_projection * glm::dvec4(ndc_x, ndc_y, ndc_mid, 1.0);
            const glm::dvec3 start = glm::dvec3(a) / a.w;
            const glm::dvec3 direction = glm::normalize(glm::dvec3(b) / b.w - start);
            if (!(direction.z < 0.0)) continue;
            // View depth along the ray: -(start.z + t direction.z); the rasteriser keeps (near, far).
            const double t_far = (-far_plane - start.z) / direction.z;
            const glm::dvec3 world_start = glm::dvec3(inverse_view * glm::dvec4(start, 1.0));
            const glm::dvec3 world_direction = glm::normalize(glm::dmat3(inverse_view) * direction);
            TruthScene::Hit hit;
            if (!scene_.intersect(glm::vec3(world_start), glm::vec3(world_direction), 0.0f, float(t_far), &hit)) continue;
            const glm::dvec3 p = world_start + double(hit.distance) * world_direction;
            glm::vec3 n = hit.normal;
            if (glm::dot(glm::dvec3(n), world_direction) > 0.0) n = -n;
            position_[index] = glm::vec3(p);
            normal_[index] = n;
            view_depth_[index] = float(-(start.z + double(hit.distance) * direction.z));
            mask_[index] = 1;
            triangles_[index] = hit.triangle;
        }
    });
    cancelled_ = options_.cancel && options_.cancel->load();
    geometry_pixels_ = size_t(std::count(mask_.begin(), mask_.end(), uint8_t(1)));
}

void GeometryTruth::trace_row(int y, int first_ray, int rays, std::vector<float>& distances, std::vector<float>& rho,
                              std::vector<glm::vec3>& directions) {
    const size_t pixels = size_t(width_) * size_t(height_);
    // Every ray of the row first (misses at +infinity, whose rho is 0), then each falloff over the whole row in one
    // obscura_evaluate_falloff call: the call resolves the settings, which per pixel cost as much as the rays.
    distances.clear();
    directions.clear();
    for (int x = 0; x < width_; ++x) {
        const size_t index = size_t(y) * size_t(width_) + size_t(x);
        if (!mask_[index]) continue;
        const glm::vec3 n = normal_[index];
        glm::vec3 t, b;
        tangent_frame(n, &t, &b);
        const glm::vec3 origin = position_[index] + scene_.surface_offset(position_[index]) * n;
        for (int i = 0; i < rays; ++i) {
            const glm::vec3 local = truth_ray_direction(uint32_t(first_ray + i), rotation_[index]);
            const glm::vec3 direction = glm::normalize(local.x * t + local.y * b + local.z * n);
            TruthScene::Hit hit;
            const bool hit_something =
                scene_.intersect(origin, direction, 0.0f, std::numeric_limits<float>::infinity(), &hit);
            distances.push_back(hit_something ? hit.distance : std::numeric_limits<float>::infinity());
            directions.push_back(direction);
        }
    }
    rho.resize(distances.size());
    for (size_t k = 0; k < falloffs_.size(); ++k) {
        // Checked in the constructor: these settings are accepted.
        if (!distances.empty()) {
            obscura_evaluate_falloff(&falloffs_[k], distances.data(), rho.data(), uint32_t(distances.size()));
        }
        size_t ray = 0;
        for (int x = 0; x < width_; ++x) {
            const size_t index = size_t(y) * size_t(width_) + size_t(x);
            // The batch continues the pixel's running sums, ray after ray, so the result does not depend on how
            // the rays were split into batches.
            double sum = sums_[k * pixels + index];
            glm::dvec3 bent = bent_sums_[k * pixels + index];
            if (mask_[index]) {
                for (int i = 0; i < rays; ++i, ++ray) {
                    sum += double(rho[ray]);
                    bent += (1.0 - double(rho[ray])) * glm::dvec3(directions[ray]);
                }
            }
            batch_[k * pixels + index] = sum;
            bent_batch_[k * pixels + index] = bent;
        }
    }
}

bool GeometryTruth::trace(int rays, const std::atomic<bool>* cancel) {
    if (cancelled_) return false;
    if (rays <= 0) return true;
    struct Scratch {
        std::vector<float> distances, rho;
        std::vector<glm::vec3> directions;
    };
    const int first_ray = rays_traced_;
    parallel_rows<Scratch>(height_, options_.threads, cancel,
                           [&](int y, Scratch& scratch) {
                               trace_row(y, first_ray, rays, scratch.distances, scratch.rho, scratch.directions);
                           });
    if (cancel && cancel->load()) return false;
    sums_.swap(batch_);
    bent_sums_.swap(bent_batch_);
    rays_traced_ += rays;
    return true;
}

FloatImage GeometryTruth::visibility(size_t index) const {
    if (index >= falloffs_.size()) throw std::out_of_range("geometry truth: no such falloff");
    FloatImage image;
    image.width = width_;
    image.height = height_;
    image.channels = 1;
    const size_t pixels = size_t(width_) * size_t(height_);
    image.pixels.assign(pixels, 1.0f);
    if (rays_traced_ == 0) return image;
    for (size_t i = 0; i < pixels; ++i) {
        if (!mask_[i]) continue;
        const double obscurance = sums_[index * pixels + i] / double(rays_traced_);
        image.pixels[i] = float(std::clamp(1.0 - obscurance, 0.0, 1.0));
    }
    return image;
}

FloatImage GeometryTruth::bent_normal(size_t index) const {
    if (index >= falloffs_.size()) throw std::out_of_range("geometry truth: no such falloff");
    FloatImage image;
    image.width = width_;
    image.height = height_;
    image.channels = 3;
    const size_t pixels = size_t(width_) * size_t(height_);
    image.pixels.assign(pixels * 3, 0.0f);
    for (size_t i = 0; i < pixels; ++i) {
        glm::dvec3 bent(0.0, 0.0, 1.0);
        if (mask_[i]) {
            const glm::dvec3 sum = bent_sums_[index * pixels + i];
            const double length = glm::length(sum);
            bent = world_to_view_ * (length > 0.0 ? sum / length : glm::dvec3(normal_[i]));
            bent = glm::normalize(bent);
        }
        for (int c = 0; c < 3; ++c) image.pixels[i * 3 + size_t(c)] = float(bent[c]);
    }
    return image;
}

FloatImage GeometryTruth::view_depth() const {
    FloatImage image;
    image.width = width_;
    image.height = height_;
    image.channels = 1;
    image.pixels = view_depth_;
    return image;
}

}  // namespace obscura::samples
