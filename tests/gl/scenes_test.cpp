// The scene library of the samples: every built-in scene and viewpoint rasterises sensibly, meshes keep
// their conventions (winding agrees with normals), OBJ files load and auto-frame, the bunny loads when
// installed, captured depth files round-trip (linear and hardware, with a guard band), and the
// analytic scene's mesh is exactly the geometry analytic_ao.h ray-casts.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "analytic_ao.h"
#include "depth_file.h"
#include "gl_test_support.h"
#include "image_io.h"
#include "scene_library.h"

namespace obscura_test {
namespace {

using obscura::samples::Camera;
using obscura::samples::DepthFileKind;
using obscura::samples::DepthFileOptions;
using obscura::samples::FloatImage;
using obscura::samples::NamedCamera;
using obscura::samples::RenderedScene;
using obscura::samples::Scene;
using obscura::samples::SceneMesh;
using obscura::samples::SceneRenderOptions;
using obscura::samples::TextureReadFormat;
using obscura::samples::read_texture_region;

constexpr int kWidth = 160;
constexpr int kHeight = 90;
const char* const kBuiltIns[] = {"atrium", "terrain", "objects", "clutter", "analytic", "room", "sliding"};

// A file in the temporary directory, removed when the test ends.
class TempFile {
public:
    explicit TempFile(const std::string& name)
        : path_((std::filesystem::temp_directory_path() /
                 ("obscura_scenes_test_" + std::to_string(::getpid()) + "_" + name))
                    .string()) {}
    ~TempFile() {
        std::error_code ignored;
        std::filesystem::remove(path_, ignored);
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    const std::string& path() const { return path_; }
    void write(const std::string& text) const { std::ofstream(path_) << text; }

private:
    std::string path_;
};

// The shared GL context current, no GL error before or after; no obscura context (see GLTest).
class SceneGLTest : public ::testing::Test {
protected:
    void SetUp() override {
        shared_gl().make_current();
        ASSERT_EQ(take_gl_error(), GLenum(GL_NO_ERROR)) << "a GL error was pending before the test";
    }
    void TearDown() override {
        const GLenum error = take_gl_error();
        EXPECT_EQ(error, GLenum(GL_NO_ERROR)) << "GL error left behind: " << gl_error_name(error);
    }
};

SceneRenderOptions options_for(const Camera& camera, int width = kWidth, int height = kHeight) {
    SceneRenderOptions options;
    options.width = width;
    options.height = height;
    options.camera = camera;
    return options;
}

// What the visible rectangle of a rasterised frame shows.
struct FrameCheck {
    int pixels = 0;
    int geometry = 0;      // normal alpha 1
    int bad_depth = 0;     // geometry without a finite depth in [0, 1), or sky not at the clear value
    int bad_normal = 0;    // geometry whose normal is not unit length
    int facing_away = 0;   // geometry whose normal points clearly away from the eye (dot > 0.3)
    int min_x = 1 << 30, min_y = 1 << 30, max_x = -1, max_y = -1;  // geometry's bounding box
    double fraction() const { return pixels ? double(geometry) / pixels : 0.0; }
};

FrameCheck check_frame(const RenderedScene& scene) {
    const obscura::samples::SceneFrame& frame = scene.frame();
    const obscura_rect& rect = frame.output_rect;
    const FloatImage depth =
        read_texture_region(frame.depth_texture, rect.x, rect.y, rect.width, rect.height, TextureReadFormat::Depth);
    const FloatImage normals =
        read_texture_region(frame.normal_texture, rect.x, rect.y, rect.width, rect.height, TextureReadFormat::Rgba);
    const glm::mat4 inverse_projection = glm::inverse(glm::make_mat4(frame.projection));
    FrameCheck check;
    for (int y = 0; y < rect.height; ++y) {
        for (int x = 0; x < rect.width; ++x) {
            ++check.pixels;
            const float d = depth.at(x, y);
            if (normals.at(x, y, 3) < 0.5f) {
                check.bad_depth += d != 1.0f;
                continue;
            }
            ++check.geometry;
            check.min_x = std::min(check.min_x, x);
            check.max_x = std::max(check.max_x, x);
            check.min_y = std::min(check.min_y, y);
            check.max_y = std::max(check.max_y, y);
            check.bad_depth += !(std::isfinite(d) && d >= 0.0f && d < 1.0f);
            const glm::vec3 n(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2));
            check.bad_normal += std::fabs(glm::length(n) - 1.0f) > 0.02f;
            // The view ray through the texel centre (the projection covers the whole depth texture).
            const glm::vec2 ndc((float(rect.x + x) + 0.5f) / float(frame.depth_width) * 2.0f - 1.0f,
                                (float(rect.y + y) + 0.5f) / float(frame.depth_height) * 2.0f - 1.0f);
            const glm::vec4 point = inverse_projection * glm::vec4(ndc, 0.0f, 1.0f);
            const glm::vec3 ray = glm::normalize(glm::vec3(point) / point.w);
            check.facing_away += glm::dot(glm::normalize(n), ray) > 0.3f;
        }
    }
    return check;
}

// ---- The registry and camera helpers (no GL) ------------------------------------------------------

TEST(SceneLibrary, ListsBuiltInsInOrderThenBunny) {
    const std::vector<obscura::samples::SceneInfo> list = obscura::samples::list_scenes();
    ASSERT_EQ(list.size(), std::size(kBuiltIns) + 1);
    for (size_t i = 0; i < std::size(kBuiltIns); ++i) {
        EXPECT_EQ(list[i].name, kBuiltIns[i]);
        EXPECT_TRUE(list[i].available);
        EXPECT_FALSE(list[i].description.empty());
    }
    EXPECT_EQ(list.back().name, "bunny");
    EXPECT_EQ(list.back().available, std::filesystem::exists(obscura::samples::bunny_obj_path()));
}

TEST(SceneLibrary, UnknownNamesThrowListingTheValidOnes) {
    try {
        obscura::samples::load_scene("sponza");
        FAIL() << "no exception";
    } catch (const std::invalid_argument& error) {
        const std::string message = error.what();
        for (const char* name : kBuiltIns) EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find("bunny"), std::string::npos) << message;
        EXPECT_NE(message.find(".obj"), std::string::npos) << message;
    }
    EXPECT_THROW(obscura::samples::load_scene(""), std::invalid_argument);
    EXPECT_THROW(obscura::samples::load_scene("/no/such/file.obj"), std::runtime_error);

    const Scene scene = obscura::samples::load_scene("analytic");
    EXPECT_EQ(&obscura::samples::find_viewpoint(scene, "box"), &scene.viewpoints[2]);
    try {
        obscura::samples::find_viewpoint(scene, "nowhere");
        FAIL() << "no exception";
    } catch (const std::invalid_argument& error) {
        const std::string message = error.what();
        for (const NamedCamera& viewpoint : scene.viewpoints) {
            EXPECT_NE(message.find(viewpoint.name), std::string::npos) << message;
        }
    }
}

TEST(SceneLibrary, OrbitCameraTurnsTheEyeAboutTheTarget) {
    Camera camera;
    camera.eye = {1.0f, 3.0f, 5.0f};
    camera.target = {1.0f, 1.0f, 1.0f};
    const Camera turned = obscura::samples::orbit_camera(camera, 90.0f);
    // +90 degrees about +y takes the +z offset to +x.
    EXPECT_NEAR(turned.eye.x, 5.0f, 1e-5f);
    EXPECT_NEAR(turned.eye.y, 3.0f, 1e-5f);
    EXPECT_NEAR(turned.eye.z, 1.0f, 1e-5f);
    EXPECT_EQ(turned.target, camera.target);
    EXPECT_EQ(turned.fov_y_degrees, camera.fov_y_degrees);
    const Camera back = obscura::samples::orbit_camera(turned, -90.0f);
    EXPECT_NEAR(glm::length(back.eye - camera.eye), 0.0f, 1e-5f);
}

TEST(SceneLibrary, FrameBoundsSeesTheWholeBox) {
    const glm::vec3 lo(-3.0f, 0.5f, 10.0f), hi(1.0f, 2.0f, 11.0f);
    const Camera camera = obscura::samples::frame_bounds(lo, hi, 45.0f);
    for (float aspect : {1.0f, 16.0f / 9.0f}) {
        const obscura::samples::Projection projection = obscura::samples::make_projection(
            obscura::samples::ProjectionKind::Perspective, camera, aspect, false);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
            const glm::vec4 clip = projection.matrix * camera.view() * glm::vec4(p, 1.0f);
            const glm::vec3 ndc = glm::vec3(clip) / clip.w;
            EXPECT_GT(clip.w, 0.0f);
            EXPECT_LT(std::fabs(ndc.x), 1.0f) << "corner " << corner << " aspect " << aspect;
            EXPECT_LT(std::fabs(ndc.y), 1.0f) << "corner " << corner << " aspect " << aspect;
            EXPECT_LT(std::fabs(ndc.z), 1.0f) << "corner " << corner << " aspect " << aspect;
        }
    }
}

// Every built-in mesh keeps the MeshBuilder conventions: unit normals, and each triangle wound
// counter-clockwise seen from the side its normals point to (so normals are consistent).
TEST(SceneLibrary, BuiltInMeshesAreConsistent) {
    for (const char* name : kBuiltIns) {
        SCOPED_TRACE(name);
        const Scene scene = obscura::samples::load_scene(name);
        EXPECT_EQ(scene.name, name);
        const SceneMesh& mesh = scene.mesh;
        ASSERT_GT(mesh.triangle_count(), 0);
        EXPECT_LT(mesh.triangle_count(), 200000);
        EXPECT_EQ(mesh.vertices.size() % 18, 0u);
        int bad_normals = 0, against_winding = 0;
        for (size_t t = 0; t + 17 < mesh.vertices.size(); t += 18) {
            glm::vec3 p[3], n[3];
            for (int k = 0; k < 3; ++k) {
                const float* v = &mesh.vertices[t + size_t(k) * 6];
                p[k] = glm::vec3(v[0], v[1], v[2]);
                n[k] = glm::vec3(v[3], v[4], v[5]);
                bad_normals += std::fabs(glm::length(n[k]) - 1.0f) > 1e-4f;
            }
            const glm::vec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
            if (glm::length(cross) < 1e-9f) continue;  // degenerate slivers say nothing
            // Every vertex normal on the front side of the face (smooth normals included).
            against_winding += glm::dot(cross, n[0]) <= 0.0f || glm::dot(cross, n[1]) <= 0.0f ||
                               glm::dot(cross, n[2]) <= 0.0f;
        }
        EXPECT_EQ(bad_normals, 0);
        EXPECT_EQ(against_winding, 0);

        ASSERT_GE(scene.viewpoints.size(), 3u);
        EXPECT_LE(scene.viewpoints.size(), 5u);
        EXPECT_EQ(scene.viewpoints[0].name, "default");
        std::set<std::string> names;
        for (const NamedCamera& viewpoint : scene.viewpoints) {
            EXPECT_TRUE(names.insert(viewpoint.name).second) << "duplicate viewpoint " << viewpoint.name;
            EXPECT_GT(viewpoint.camera.near_plane, 0.0f);
            EXPECT_GT(viewpoint.camera.far_plane, 10.0f * viewpoint.camera.near_plane);
        }
        for (int axis = 0; axis < 3; ++axis) EXPECT_LE(scene.bounds_min[axis], scene.bounds_max[axis]);
    }
}

// ---- Rasterising the built-in scenes ------------------------------------------------------------

class BuiltInScene : public SceneGLTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(BuiltInScene, EveryViewpointRasterises) {
    const Scene scene = obscura::samples::load_scene(GetParam());
    for (const NamedCamera& viewpoint : scene.viewpoints) {
        SCOPED_TRACE(viewpoint.name);
        const RenderedScene rendered = obscura::samples::render_scene(scene.mesh, options_for(viewpoint.camera));
        const FrameCheck check = check_frame(rendered);
        ASSERT_EQ(check.pixels, kWidth * kHeight);
        // Every scene fills most of its default view (measured: 74 % at least, terrain); the other
        // viewpoints show at least a quarter geometry (measured: 47 % at least, terrain overview).
        EXPECT_GT(check.fraction(), viewpoint.name == "default" ? 0.5 : 0.25);
        EXPECT_EQ(check.bad_depth, 0);
        EXPECT_EQ(check.bad_normal, 0);
        // Closed geometry with outward normals: the camera sees front faces only (a few silhouette
        // texels of smooth shapes interpolate a normal that turns slightly away).
        EXPECT_LE(check.facing_away, check.geometry / 200)  // measured: 8 of 13667 at most (atrium gallery)
            << check.facing_away << " of " << check.geometry;
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, BuiltInScene, ::testing::ValuesIn(kBuiltIns),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                             return std::string(param_info.param);
                         });

TEST_F(SceneGLTest, RenderDemoSceneIsTheRoomScene) {
    // render_demo_scene stays a thin wrapper: the same depth as render_scene of the room's mesh.
    const Scene room = obscura::samples::load_scene("room");
    const SceneRenderOptions options = options_for(room.viewpoints[0].camera);
    const RenderedScene a = obscura::samples::render_demo_scene(options);
    const RenderedScene b = obscura::samples::render_scene(room.mesh, options);
    const obscura_rect& rect = a->output_rect;
    const FloatImage da = read_texture_region(a->depth_texture, 0, 0, a->depth_width, a->depth_height,
                                              TextureReadFormat::Depth);
    const FloatImage db = read_texture_region(b->depth_texture, 0, 0, b->depth_width, b->depth_height,
                                              TextureReadFormat::Depth);
    EXPECT_EQ(rect.width, kWidth);
    EXPECT_EQ(da.pixels, db.pixels);
    EXPECT_THROW(obscura::samples::render_scene(SceneMesh{}, options), std::invalid_argument);
}

// ---- OBJ files ------------------------------------------------------------------------------------

TEST_F(SceneGLTest, ObjCubeLoadsAndAutoFrames) {
    // A 2 m cube far from the origin, quads only, no normals: triangulated, per-face normals outwards.
    TempFile obj("cube.obj");
    obj.write("# cube\n"
              "v 9 1 -21\nv 11 1 -21\nv 11 3 -21\nv 9 3 -21\n"
              "v 9 1 -19\nv 11 1 -19\nv 11 3 -19\nv 9 3 -19\n"
              "f 5 6 7 8\nf 2 1 4 3\nf 1 5 8 4\nf 6 2 3 7\nf 8 7 3 4\nf 1 2 6 5\n");
    const Scene scene = obscura::samples::load_scene(obj.path());
    EXPECT_EQ(scene.name, obj.path());
    ASSERT_EQ(scene.mesh.triangle_count(), 12);
    EXPECT_EQ(scene.bounds_min, glm::vec3(9.0f, 1.0f, -21.0f));
    EXPECT_EQ(scene.bounds_max, glm::vec3(11.0f, 3.0f, -19.0f));
    const glm::vec3 centre(10.0f, 2.0f, -20.0f);
    for (size_t v = 0; v < scene.mesh.vertices.size(); v += 6) {
        const float* f = &scene.mesh.vertices[v];
        const glm::vec3 p(f[0], f[1], f[2]), n(f[3], f[4], f[5]);
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(n, p - centre), 1.0f, 1e-5f) << "face normals point out of the cube";
    }
    ASSERT_EQ(scene.viewpoints.size(), 4u);
    for (const NamedCamera& viewpoint : scene.viewpoints) {
        SCOPED_TRACE(viewpoint.name);
        const RenderedScene rendered = obscura::samples::render_scene(scene.mesh, options_for(viewpoint.camera));
        const FrameCheck check = check_frame(rendered);
        EXPECT_GT(check.fraction(), 0.05);
        EXPECT_EQ(check.bad_depth, 0);
        EXPECT_EQ(check.facing_away, 0);
        // All of it in view: its pixels stay off the image border.
        EXPECT_GT(check.min_x, 0);
        EXPECT_GT(check.min_y, 0);
        EXPECT_LT(check.max_x, kWidth - 1);
        EXPECT_LT(check.max_y, kHeight - 1);
    }
}

// The same cube wound clockwise (every face reversed): its normals, from the winding, point into it. The rasteriser
// turns each fragment's normal towards the camera, as the geometry truth turns its own, so a host passing the
// scene's normals (--normals) gives the SDK normals on the viewer's side (they pointed into the surface before:
// up to 0.43 of AO apart from the reconstructed normals' on such a mesh).
TEST_F(SceneGLTest, ObjNormalsFaceTheCameraWhateverTheWinding) {
    TempFile obj("cube_cw.obj");
    obj.write("v 9 1 -21\nv 11 1 -21\nv 11 3 -21\nv 9 3 -21\n"
              "v 9 1 -19\nv 11 1 -19\nv 11 3 -19\nv 9 3 -19\n"
              "f 8 7 6 5\nf 3 4 1 2\nf 4 8 5 1\nf 7 3 2 6\nf 4 3 7 8\nf 5 6 2 1\n");
    const Scene scene = obscura::samples::load_scene(obj.path());
    ASSERT_EQ(scene.mesh.triangle_count(), 12);
    const RenderedScene rendered = obscura::samples::render_scene(scene.mesh, options_for(scene.viewpoints[0].camera));
    const FrameCheck check = check_frame(rendered);
    EXPECT_GT(check.fraction(), 0.05);
    EXPECT_EQ(check.facing_away, 0);
}

TEST(SceneLibrary, ObjNormalsComeFromTheFile) {
    // One triangle wound towards +z whose file normals say -z: the file wins. A degenerate face
    // without normals is dropped; a file without faces is an error.
    TempFile obj("normals.obj");
    // A vertex past the float range (1e400) drops its face, file normals or not (its rays would be NaN).
    obj.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 2 2\nv 1e400 1 0\nvn 0 0 -2\n"
              "f 1//1 2//1 3//1\nf 4 4 4\nf 5//1 2//1 3//1\n");
    const Scene scene = obscura::samples::load_scene(obj.path());
    ASSERT_EQ(scene.mesh.triangle_count(), 1);
    EXPECT_TRUE(std::isfinite(scene.bounds_max.x));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(scene.mesh.vertices[size_t(k) * 6 + 5], -1.0f);
    TempFile empty("empty.OBJ");
    empty.write("v 0 0 0\n");
    EXPECT_THROW(obscura::samples::load_scene(empty.path()), std::runtime_error);
}

TEST_F(SceneGLTest, BunnyLoadsWhenInstalled) {
    if (!std::filesystem::exists(obscura::samples::bunny_obj_path())) {
        GTEST_SKIP() << obscura::samples::bunny_obj_path() << " not installed (glmark2-data)";
    }
    const Scene scene = obscura::samples::load_scene("bunny");
    EXPECT_GT(scene.mesh.triangle_count(), 60000);
    EXPECT_NEAR(scene.bounds_min.y, 0.0f, 1e-5f);  // the floor, the bunny standing on it
    const RenderedScene rendered =
        obscura::samples::render_scene(scene.mesh, options_for(scene.viewpoints[0].camera));
    const FrameCheck check = check_frame(rendered);
    EXPECT_GT(check.fraction(), 0.4);
    EXPECT_EQ(check.bad_depth, 0);
    EXPECT_LE(check.facing_away, check.geometry / 100);
}

// ---- Depth files ------------------------------------------------------------------------------------

// The file's image: a tilted plane's depth seen through `projection` (covering the whole file),
// linear view depth or window depth of a standard [near, far] perspective; a few sky texels.
constexpr int kFileWidth = 120, kFileHeight = 72;  // 100 x 60 visible with a 0.1 guard band
constexpr float kNear = 0.5f, kFar = 100.0f;

FloatImage plane_depth_image(const glm::mat4& projection, bool hardware) {
    const glm::vec3 normal = glm::normalize(glm::vec3(0.3f, 0.6f, 1.0f));
    const glm::vec3 on_plane(0.0f, 0.0f, -6.0f);
    const glm::mat4 inverse = glm::inverse(projection);
    FloatImage image;
    image.width = kFileWidth;
    image.height = kFileHeight;
    for (int y = 0; y < kFileHeight; ++y) {
        for (int x = 0; x < kFileWidth; ++x) {
            const glm::vec2 ndc((float(x) + 0.5f) / kFileWidth * 2.0f - 1.0f,
                                (float(y) + 0.5f) / kFileHeight * 2.0f - 1.0f);
            const glm::vec4 point = inverse * glm::vec4(ndc, 0.0f, 1.0f);
            const glm::vec3 ray = glm::vec3(point) / point.w;
            const float t = glm::dot(normal, on_plane) / glm::dot(normal, ray);
            const float view_depth = -(t * ray).z;
            float value = hardware ? kFar * (view_depth - kNear) / (view_depth * (kFar - kNear)) : view_depth;
            if (x < 3 && y < 2) value = hardware ? 1.0f : (x == 0 ? 0.0f : (x == 1 ? NAN : INFINITY));
            image.pixels.push_back(value);
        }
    }
    return image;
}

// The projection load_depth_file must produce, written out independently: a symmetric perspective of
// the visible 100 x 60 rectangle, scaled by visible / file size (the guard band is symmetric here).
glm::mat4 expected_projection(float fov_y_degrees) {
    glm::mat4 matrix = glm::perspective(glm::radians(fov_y_degrees), 100.0f / 60.0f, kNear, kFar);
    matrix[0][0] *= 100.0f / kFileWidth;
    matrix[1][1] *= 60.0f / kFileHeight;
    return matrix;
}

DepthFileOptions depth_options(const std::string& path, DepthFileKind kind) {
    DepthFileOptions options;
    options.path = path;
    options.kind = kind;
    options.fov_y_degrees = 50.0f;
    options.guard_band = 0.1f;
    options.near_plane = kNear;
    options.far_plane = kFar;
    return options;
}

void expect_frame_layout(const obscura::samples::SceneFrame& frame) {
    EXPECT_EQ(frame.depth_width, kFileWidth);
    EXPECT_EQ(frame.depth_height, kFileHeight);
    EXPECT_EQ(frame.output_rect.x, 10);
    EXPECT_EQ(frame.output_rect.y, 6);
    EXPECT_EQ(frame.output_rect.width, 100);
    EXPECT_EQ(frame.output_rect.height, 60);
    EXPECT_EQ(frame.normal_texture, 0u);
    const glm::mat4 expected = expected_projection(50.0f);
    for (int i = 0; i < 16; ++i) {
        const float e = glm::value_ptr(expected)[i];
        EXPECT_NEAR(frame.projection[i], e, 1e-5f * std::fabs(e) + 1e-6f) << "element " << i;
    }
}

class DepthFileTest : public GLTest {};

// A header that claims more than the file holds is refused before anything is allocated (a 100000x100000 header
// once zero-filled 40 GB before the read found the file short).
TEST(PfmFile, HeaderLargerThanTheFileIsRefusedBeforeAllocating) {
    TempFile pfm("claims_too_much.pfm");
    {
        std::ofstream file(pfm.path(), std::ios::binary);
        file << "Pf\n100000 100000\n-1.0\n";
        const float some[4] = {1.0f, 2.0f, 3.0f, 4.0f};
        file.write(reinterpret_cast<const char*>(some), sizeof some);
    }
    try {
        obscura::samples::read_pfm(pfm.path());
        ADD_FAILURE() << "read_pfm accepted a truncated file";
    } catch (const std::runtime_error& error) {
        EXPECT_NE(std::string(error.what()).find("truncated: its header says 100000x100000"), std::string::npos)
            << error.what();
    }
}

TEST_F(DepthFileTest, LinearRoundTrip) {
    TempFile pfm("linear.pfm");
    const FloatImage written = plane_depth_image(expected_projection(50.0f), false);
    obscura::samples::write_pfm(pfm.path(), written);
    const RenderedScene loaded = obscura::samples::load_depth_file(depth_options(pfm.path(), DepthFileKind::Linear));
    const obscura::samples::SceneFrame& frame = loaded.frame();
    EXPECT_EQ(frame.depth_kind, OBSCURA_DEPTH_LINEAR_VIEW);
    EXPECT_EQ(frame.depth_internal_format, GLenum(GL_R32F));
    EXPECT_EQ(frame.make_input(true).depth_kind, OBSCURA_DEPTH_LINEAR_VIEW);
    EXPECT_EQ(frame.make_input(true).normal_texture, 0u);
    expect_frame_layout(frame);

    const FloatImage read = read_texture_region(frame.depth_texture, 0, 0, kFileWidth, kFileHeight);
    for (int y = 0; y < kFileHeight; ++y) {
        for (int x = 0; x < kFileWidth; ++x) {
            const float w = written.at(x, y);
            const bool sky = !std::isfinite(w) || w == 0.0f;
            if (sky) {
                EXPECT_TRUE(std::isinf(read.at(x, y)) && read.at(x, y) > 0.0f) << x << ", " << y;
            } else {
                EXPECT_EQ(read.at(x, y), w) << x << ", " << y;
            }
        }
    }
    // The SDK takes it as is: a plane occludes nothing.
    const std::vector<float> ao = render_to_new_texture(ctx(), frame.make_input(), make_settings(1.0f), GL_R32F, 1);
    ASSERT_EQ(ao.size(), size_t(100 * 60));
    EXPECT_GT(*std::min_element(ao.begin(), ao.end()), 0.95f);
}

TEST_F(DepthFileTest, HardwareRoundTripMatchesLinear) {
    TempFile hardware_pfm("hardware.pfm"), linear_pfm("linear.pfm");
    const FloatImage written = plane_depth_image(expected_projection(50.0f), true);
    obscura::samples::write_pfm(hardware_pfm.path(), written);
    obscura::samples::write_pfm(linear_pfm.path(), plane_depth_image(expected_projection(50.0f), false));
    const RenderedScene hardware =
        obscura::samples::load_depth_file(depth_options(hardware_pfm.path(), DepthFileKind::Hardware));
    EXPECT_EQ(hardware->depth_kind, OBSCURA_DEPTH_HARDWARE);
    EXPECT_EQ(hardware->depth_internal_format, GLenum(GL_DEPTH_COMPONENT32F));
    EXPECT_FALSE(hardware->reversed_z);
    expect_frame_layout(hardware.frame());
    const FloatImage read =
        read_texture_region(hardware->depth_texture, 0, 0, kFileWidth, kFileHeight, TextureReadFormat::Depth);
    EXPECT_EQ(read.pixels, written.pixels);

    // The same plane as linear depth gives the same AO (a plane: ~1 everywhere either way).
    const RenderedScene linear =
        obscura::samples::load_depth_file(depth_options(linear_pfm.path(), DepthFileKind::Linear));
    const std::vector<float> a = render_to_new_texture(ctx(), hardware->make_input(), make_settings(1.0f), GL_R32F, 1);
    const std::vector<float> b = render_to_new_texture(ctx(), linear->make_input(), make_settings(1.0f), GL_R32F, 1);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(a[i], b[i], 0.01f) << i;
}

TEST_F(DepthFileTest, RasterisedSceneRoundTrips) {
    // Depth rasterised by render_scene (reversed-Z, infinite far, guard band), written to a file and
    // loaded back as hardware depth, and converted to linear depth: the same AO as the original.
    const Scene scene = obscura::samples::load_scene("objects");
    SceneRenderOptions options = options_for(scene.viewpoints[0].camera);
    options.projection = obscura::samples::ProjectionKind::ReversedInfinite;
    options.normals = false;
    const RenderedScene original = obscura::samples::render_scene(scene.mesh, options);
    const FloatImage depth = read_texture_region(original->depth_texture, 0, 0, original->depth_width,
                                                 original->depth_height, TextureReadFormat::Depth);
    TempFile hardware_pfm("scene_hardware.pfm"), linear_pfm("scene_linear.pfm");
    obscura::samples::write_pfm(hardware_pfm.path(), depth);
    FloatImage linear = depth;
    const float near_plane = scene.viewpoints[0].camera.near_plane;
    // Reversed infinite: window depth = near / view depth; sky (0) stays 0.
    for (float& value : linear.pixels) value = value > 0.0f ? near_plane / value : 0.0f;
    obscura::samples::write_pfm(linear_pfm.path(), linear);

    DepthFileOptions file_options;
    file_options.kind = DepthFileKind::Hardware;
    file_options.fov_y_degrees = options.camera.fov_y_degrees;
    file_options.guard_band = options.guard_band;
    file_options.near_plane = near_plane;
    file_options.far_plane = std::numeric_limits<float>::infinity();
    file_options.reversed_z = true;
    file_options.path = hardware_pfm.path();
    const RenderedScene from_hardware = obscura::samples::load_depth_file(file_options);
    file_options.kind = DepthFileKind::Linear;
    file_options.path = linear_pfm.path();
    const RenderedScene from_linear = obscura::samples::load_depth_file(file_options);
    EXPECT_EQ(from_hardware->output_rect.x, original->output_rect.x);
    EXPECT_EQ(from_hardware->output_rect.width, original->output_rect.width);

    const obscura_settings settings = make_settings(0.5f);
    const std::vector<float> reference = render_to_new_texture(ctx(), original->make_input(), settings, GL_R32F, 1);
    for (const RenderedScene* loaded : {&from_hardware, &from_linear}) {
        const std::vector<float> ao = render_to_new_texture(ctx(), (*loaded)->make_input(), settings, GL_R32F, 1);
        ASSERT_EQ(ao.size(), reference.size());
        double sum = 0.0, lowest = 1.0;
        for (size_t i = 0; i < ao.size(); ++i) {
            sum += std::fabs(double(ao[i]) - reference[i]);
            lowest = std::min(lowest, double(reference[i]));
        }
        const bool is_linear = (*loaded)->depth_kind == OBSCURA_DEPTH_LINEAR_VIEW;
        EXPECT_LT(sum / double(ao.size()), 1e-3) << (is_linear ? "linear" : "hardware");  // measured: 0
        EXPECT_LT(lowest, 0.8);  // the scene does have occlusion to compare
    }
}

TEST_F(SceneGLTest, BadDepthFilesThrow) {
    TempFile good("good.pfm"), rgb("rgb.pfm"), negative("negative.pfm"), outside("outside.pfm");
    FloatImage image;
    image.width = 8;
    image.height = 4;
    image.pixels.assign(32, 0.5f);
    obscura::samples::write_pfm(good.path(), image);
    FloatImage colour = image;
    colour.channels = 3;
    colour.pixels.assign(96, 0.5f);
    obscura::samples::write_pfm(rgb.path(), colour);
    image.pixels[5] = -1.0f;
    obscura::samples::write_pfm(negative.path(), image);
    image.pixels[5] = 1.5f;
    obscura::samples::write_pfm(outside.path(), image);

    auto load = [](const std::string& path, DepthFileKind kind) {
        DepthFileOptions options;
        options.path = path;
        options.kind = kind;
        return obscura::samples::load_depth_file(options);
    };
    EXPECT_NO_THROW(load(good.path(), DepthFileKind::Linear));
    EXPECT_NO_THROW(load(good.path(), DepthFileKind::Hardware));
    EXPECT_THROW(load(good.path() + ".missing", DepthFileKind::Linear), std::runtime_error);
    EXPECT_THROW(load(rgb.path(), DepthFileKind::Linear), std::runtime_error);
    EXPECT_THROW(load(negative.path(), DepthFileKind::Linear), std::runtime_error);
    EXPECT_THROW(load(outside.path(), DepthFileKind::Hardware), std::runtime_error);
    EXPECT_NO_THROW(load(outside.path(), DepthFileKind::Linear));
    try {
        load(negative.path(), DepthFileKind::Linear);
    } catch (const std::runtime_error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find(negative.path()), std::string::npos) << message;
        EXPECT_NE(message.find("(5, 0)"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }

    DepthFileOptions options;
    options.path = good.path();
    for (auto change : std::vector<void (*)(DepthFileOptions&)>{
             [](DepthFileOptions& o) { o.path.clear(); },
             [](DepthFileOptions& o) { o.fov_y_degrees = 0.0f; },
             [](DepthFileOptions& o) { o.fov_y_degrees = 180.0f; },
             [](DepthFileOptions& o) { o.guard_band = 1.0f; },
             [](DepthFileOptions& o) { o.guard_band = -0.1f; },
             [](DepthFileOptions& o) { o.near_plane = 0.0f; },
             [](DepthFileOptions& o) { o.far_plane = o.near_plane; },
             [](DepthFileOptions& o) { o.far_plane = NAN; }}) {
        DepthFileOptions bad = options;
        change(bad);
        EXPECT_THROW(obscura::samples::load_depth_file(bad), std::invalid_argument);
    }
    EXPECT_EQ(obscura::samples::parse_depth_file_kind("hardware"), DepthFileKind::Hardware);
    EXPECT_THROW(obscura::samples::parse_depth_file_kind("log"), std::invalid_argument);
}

// ---- The analytic scene: mesh and ray caster agree ----------------------------------------------

bool on_surface(const obscura::samples::AnalyticPrimitive& primitive, const glm::dvec3& p, double epsilon) {
    for (int axis = 0; axis < 3; ++axis) {
        if (p[axis] < primitive.lo[axis] - epsilon || p[axis] > primitive.hi[axis] + epsilon) return false;
    }
    if (primitive.kind == obscura::samples::AnalyticPrimitive::Kind::Rectangle) return true;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::fabs(p[axis] - primitive.lo[axis]) < epsilon || std::fabs(p[axis] - primitive.hi[axis]) < epsilon) {
            return true;
        }
    }
    return false;
}

TEST(AnalyticScene, MeshLiesOnThePrimitives) {
    const Scene scene = obscura::samples::load_scene("analytic");
    const auto& primitives = obscura::samples::analytic_scene_primitives();
    const std::vector<float>& v = scene.mesh.vertices;
    ASSERT_FALSE(v.empty());
    for (size_t i = 0; i < v.size(); i += 6) {
        const glm::dvec3 p(v[i], v[i + 1], v[i + 2]);
        bool found = false;
        for (const auto& primitive : primitives) found = found || on_surface(primitive, p, 1e-6);
        EXPECT_TRUE(found) << "vertex " << p.x << ", " << p.y << ", " << p.z;
    }
    // A ray cast back at each triangle's centroid from 1 cm in front of it hits there, facing like the mesh.
    for (size_t t = 0; t < v.size(); t += 18) {
        glm::dvec3 centroid(0.0);
        for (size_t k = 0; k < 3; ++k) centroid += glm::dvec3(v[t + k * 6], v[t + k * 6 + 1], v[t + k * 6 + 2]);
        centroid /= 3.0;
        const glm::dvec3 n(v[t + 3], v[t + 4], v[t + 5]);
        double distance = 0.0;
        glm::dvec3 hit_normal(0.0);
        ASSERT_TRUE(obscura::samples::cast_ray(primitives, centroid + 0.01 * n, -n, &distance, &hit_normal));
        EXPECT_NEAR(distance, 0.01, 1e-6);
        EXPECT_EQ(hit_normal, n);
    }
}

TEST_F(SceneGLTest, AnalyticDepthMatchesRayCasting) {
    // Every texel's rasterised view depth equals the ray-cast distance along the texel's ray (relative
    // 1e-4; a GPU's rasteriser interpolates depth its own way, so a few texels in a thousand may reach
    // 1e-3), and sky is where rays miss; edge texels may disagree on coverage.
    const Scene scene = obscura::samples::load_scene("analytic");
    const Camera& camera = scene.viewpoints[0].camera;
    const RenderedScene rendered = obscura::samples::render_scene(scene.mesh, options_for(camera));
    const obscura::samples::SceneFrame& frame = rendered.frame();
    const FloatImage depth =
        read_texture_region(frame.depth_texture, 0, 0, frame.depth_width, frame.depth_height, TextureReadFormat::Depth);
    const glm::dmat4 inverse_projection = glm::inverse(glm::dmat4(glm::make_mat4(frame.projection)));
    const glm::dmat4 inverse_view = glm::inverse(glm::dmat4(frame.view));
    const double n = frame.near_plane, f = frame.far_plane;
    int mismatched_coverage = 0, compared = 0, hits = 0;
    double worst = 0.0;
    for (int y = 0; y < frame.depth_height; ++y) {
        for (int x = 0; x < frame.depth_width; ++x) {
            const glm::dvec4 ndc((x + 0.5) / frame.depth_width * 2.0 - 1.0, (y + 0.5) / frame.depth_height * 2.0 - 1.0,
                                 0.0, 1.0);
            const glm::dvec4 view_point = inverse_projection * ndc;
            const glm::dvec3 view_ray = glm::dvec3(view_point) / view_point.w;
            const glm::dvec3 world_ray = glm::dvec3(inverse_view * glm::dvec4(view_ray, 0.0));
            double t = 0.0;
            const bool hit = obscura::samples::cast_ray(obscura::samples::analytic_scene_primitives(),
                                                        glm::dvec3(camera.eye), world_ray, &t, nullptr);
            const double window = depth.at(x, y);
            if (hit != (window < 1.0)) {
                ++mismatched_coverage;
                continue;
            }
            if (!hit) continue;
            ++hits;
            const double expected = -(t * view_ray).z;
            const double rasterised = n * f / (f - window * (f - n));  // standard [-1, 1] perspective
            compared += std::fabs(rasterised - expected) > 1e-4 * expected;
            worst = std::max(worst, std::fabs(rasterised - expected) / expected);
        }
    }
    EXPECT_GT(hits, frame.depth_width * frame.depth_height / 2);
    EXPECT_LE(compared, hits / 1000);
    EXPECT_LT(worst, 1e-3);
    EXPECT_LE(mismatched_coverage, frame.depth_width);
    RecordProperty("texels_over_1e-4", compared);
    RecordProperty("worst_relative_error", std::to_string(worst));
}

}  // namespace
}  // namespace obscura_test
