// Every allocation the SDK makes can fail, and the host must be able to go on. A host loader plays a GL that runs
// out of memory at the n-th allocation (glTexStorage2D/3D, glBufferData, and glCompileShader and glLinkProgram, for
// which drivers allocate: the call does nothing and the next glGetError answers GL_OUT_OF_MEMORY), and the host
// allocator returns NULL when the n-th allocation is one of its
// own, for every n that a context's creation, its obscura_prepare and its first two frames make, for every method
// and the paths around them (reduced resolution, temporal history, bent normals, the blit to a host framebuffer).
// Each failure must
//   - return OBSCURA_STATUS_OUT_OF_MEMORY from the call that made the allocation (create, prepare or render), with a
//     message, and be noticed there (the SDK reads the error it was given);
//   - leave no GL error and no host GL state changed;
//   - leave the context whole: the same frames rendered again, nothing failing, give the image of a context that
//     never failed, bit for bit, and the same memory report;
//   - leave no GL object and no host allocation behind once the context is destroyed.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "ao_test_scene.h"
#include "gl_state_snapshot.h"
#include "gl_test_support.h"

namespace obscura_test {
namespace {

constexpr int kWidth = 64, kHeight = 48;

// The failing GL and host allocator: the GL allocation calls and glGetError wrapped (everything else is the real
// GL), and the allocator counting its live blocks.
struct FailingGL {
    static int allocations;  // GL and host allocations seen since reset()
    static int fail_at;      // the one that fails (-1: none)
    static bool pending;     // GL_OUT_OF_MEMORY (and the noise) waiting for the SDK's next glGetError calls
    // GL returns several pending errors in no set order: 0 GL_OUT_OF_MEMORY alone, 1 a GL_INVALID_OPERATION read
    // before it, 2 one read after it.
    static int noise;
    static int answered;     // errors of the pending failure read so far
    static int live_blocks;  // host allocations not yet freed

    static GLenum (*real_get_error)();
    static void (*real_tex_storage_2d)(GLenum, GLsizei, GLenum, GLsizei, GLsizei);
    static void (*real_tex_storage_3d)(GLenum, GLsizei, GLenum, GLsizei, GLsizei, GLsizei);
    static void (*real_buffer_data)(GLenum, GLsizeiptr, const void*, GLenum);
    static void (*real_compile_shader)(GLuint);
    static void (*real_link_program)(GLuint);

    static void reset(int failing) {
        allocations = 0;
        fail_at = failing;
        pending = false;
        answered = 0;
    }
    // Counts the call; true when this one is to fail (it is then not made, as GL makes no storage on
    // GL_OUT_OF_MEMORY).
    static bool fails() {
        if (allocations++ != fail_at) return false;
        pending = true;
        return true;
    }
    static GLenum get_error() {
        if (!pending) return real_get_error();
        const int count = noise == 0 ? 1 : 2;
        const bool out_of_memory = noise == 1 ? answered == 1 : answered == 0;
        if (++answered == count) {
            pending = false;
            answered = 0;
        }
        return out_of_memory ? GLenum(GL_OUT_OF_MEMORY) : GLenum(GL_INVALID_OPERATION);
    }
    static void tex_storage_2d(GLenum target, GLsizei levels, GLenum format, GLsizei width, GLsizei height) {
        if (!fails()) real_tex_storage_2d(target, levels, format, width, height);
    }
    static void tex_storage_3d(GLenum target, GLsizei levels, GLenum format, GLsizei width, GLsizei height,
                               GLsizei depth) {
        if (!fails()) real_tex_storage_3d(target, levels, format, width, height, depth);
    }
    static void buffer_data(GLenum target, GLsizeiptr size, const void* data, GLenum usage) {
        if (!fails()) real_buffer_data(target, size, data, usage);
    }
    // A driver allocates as it compiles and links: skipped, the shader is not compiled (the program not linked).
    static void compile_shader(GLuint shader) {
        if (!fails()) real_compile_shader(shader);
    }
    static void link_program(GLuint program) {
        if (!fails()) real_link_program(program);
    }

    static void* host_alloc(size_t size, void*) {
        if (allocations++ == fail_at) return nullptr;
        void* block = std::malloc(size);
        if (block) ++live_blocks;
        return block;
    }
    static void host_free(void* block, void*) {
        if (block) --live_blocks;
        std::free(block);
    }

    static obscura_gl_function loader(void*, const char* name) {
        const std::pair<const char*, obscura_gl_function> wrapped[] = {
            {"glGetError", reinterpret_cast<obscura_gl_function>(&get_error)},
            {"glTexStorage2D", reinterpret_cast<obscura_gl_function>(&tex_storage_2d)},
            {"glTexStorage3D", reinterpret_cast<obscura_gl_function>(&tex_storage_3d)},
            {"glBufferData", reinterpret_cast<obscura_gl_function>(&buffer_data)},
            {"glCompileShader", reinterpret_cast<obscura_gl_function>(&compile_shader)},
            {"glLinkProgram", reinterpret_cast<obscura_gl_function>(&link_program)},
        };
        for (const auto& [wrapped_name, function] : wrapped) {
            if (std::strcmp(name, wrapped_name) == 0) return function;
        }
        return HeadlessGL::get_proc_address(name);
    }

    static void load_real_functions() {
        auto real = [](const char* name) { return HeadlessGL::get_proc_address(name); };
        real_get_error = reinterpret_cast<decltype(real_get_error)>(real("glGetError"));
        real_tex_storage_2d = reinterpret_cast<decltype(real_tex_storage_2d)>(real("glTexStorage2D"));
        real_tex_storage_3d = reinterpret_cast<decltype(real_tex_storage_3d)>(real("glTexStorage3D"));
        real_buffer_data = reinterpret_cast<decltype(real_buffer_data)>(real("glBufferData"));
        real_compile_shader = reinterpret_cast<decltype(real_compile_shader)>(real("glCompileShader"));
        real_link_program = reinterpret_cast<decltype(real_link_program)>(real("glLinkProgram"));
    }
};
int FailingGL::allocations = 0;
int FailingGL::fail_at = -1;
bool FailingGL::pending = false;
int FailingGL::noise = 0;
int FailingGL::answered = 0;
int FailingGL::live_blocks = 0;
GLenum (*FailingGL::real_get_error)() = nullptr;
void (*FailingGL::real_tex_storage_2d)(GLenum, GLsizei, GLenum, GLsizei, GLsizei) = nullptr;
void (*FailingGL::real_tex_storage_3d)(GLenum, GLsizei, GLenum, GLsizei, GLsizei, GLsizei) = nullptr;
void (*FailingGL::real_buffer_data)(GLenum, GLsizeiptr, const void*, GLenum) = nullptr;
void (*FailingGL::real_compile_shader)(GLuint) = nullptr;
void (*FailingGL::real_link_program)(GLuint) = nullptr;

// One configuration: a method's settings, and how the host hands over its frames.
struct FailureCase {
    const char* name;
    obscura_method method;
    std::function<void(obscura_settings*)> tweak;
    bool temporal = false;      // matrices and frame indices given: the second frame reads the first's history
    bool bent_normals = false;  // GTAO's bent normals into a host texture
    bool framebuffer = false;   // the output into a host renderbuffer through a framebuffer (the SDK's blit)
    uint32_t context_flags = 0; // OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS: the GPUs' storage buffers instead of buffer textures
    int noise = 0;              // FailingGL::noise: another error read before (1) or after (2) each GL_OUT_OF_MEMORY
};

obscura_settings settings_for(const FailureCase& c) {
    obscura_settings s;
    EXPECT_EQ(obscura_default_settings(c.method, &s), OBSCURA_OK);
    if (c.method == OBSCURA_METHOD_REFERENCE) s.reference.rays = 4;
    if (c.tweak) c.tweak(&s);
    if (c.temporal) s.temporal.enabled = OBSCURA_TOGGLE_ON;
    return s;
}

const FailureCase kCases[] = {
    {"hbao", OBSCURA_METHOD_HBAO, nullptr},
    {"hbao_half_temporal", OBSCURA_METHOD_HBAO,
     [](obscura_settings* s) { s->resolution.scale = OBSCURA_RESOLUTION_HALF; }, true},
    {"hbao_framebuffer", OBSCURA_METHOD_HBAO, nullptr, false, false, true},
    {"sao", OBSCURA_METHOD_SAO, nullptr},
    {"lsao", OBSCURA_METHOD_LSAO, nullptr},
    {"ffao", OBSCURA_METHOD_FFAO, nullptr},
    {"ffao_saao", OBSCURA_METHOD_FFAO,
     [](obscura_settings* s) {
         s->ffao.saao = OBSCURA_TOGGLE_ON;
         s->ffao.sectors = 18;
     }},
    {"gtao_bent_normals_temporal", OBSCURA_METHOD_GTAO, nullptr, true, true},
    {"gtao_bitmask_half_bent_normals", OBSCURA_METHOD_GTAO,
     [](obscura_settings* s) {
         s->gtao.thickness_mode = 2;
         s->resolution.scale = OBSCURA_RESOLUTION_HALF;
     },
     false, true},
    {"reference", OBSCURA_METHOD_REFERENCE, nullptr},
    // The code paths GPUs run: LSAO's values and line records, FFAO's peaks and columns in storage buffers.
    {"lsao_gpu_code_paths", OBSCURA_METHOD_LSAO, nullptr, false, false, false, OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS},
    {"ffao_saao_gpu_code_paths", OBSCURA_METHOD_FFAO,
     [](obscura_settings* s) {
         s->ffao.saao = OBSCURA_TOGGLE_ON;
         s->ffao.sectors = 18;
     },
     false, false, false, OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS},
    // GL returns several pending errors in no set order: out of memory must still be what the call answers when
    // another error is read before it (GTAO with bent normals and temporal frames: most of the SDK's allocation kinds).
    {"gtao_out_of_memory_read_second", OBSCURA_METHOD_GTAO, nullptr, true, true, false, 0, 1},
    {"gtao_out_of_memory_read_first", OBSCURA_METHOD_GTAO, nullptr, true, true, false, 0, 2},
};

std::string case_name(const ::testing::TestParamInfo<FailureCase>& info) { return info.param.name; }

// What a context gives for the sequence: every call's status until the first that failed, the last frame's AO (and
// bent normals) when none did, and the memory it reported.
struct Outcome {
    obscura_status status = OBSCURA_OK;
    std::string failed_call, message;
    std::vector<uint8_t> image, bent;
    uint64_t memory = 0;
};

class AllocationFailure : public ::testing::TestWithParam<FailureCase> {
protected:
    void SetUp() override {
        shared_gl().make_current();
        ASSERT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
        FailingGL::load_real_functions();
        FailingGL::reset(-1);
        FailingGL::noise = GetParam().noise;
        const glm::dmat4 view = look_at(glm::dvec3(0.9, 2.4, 3.2), glm::dvec3(0.0, 0.3, 0.0));
        scene_ = std::make_unique<AoScene>(make_ao_scene(
            Projection::Perspective, view,
            {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
             box(2, glm::dvec3(-0.5, 0.0, -0.5), glm::dvec3(0.5, 0.7, 0.5))},
            Lens(), kWidth, kHeight));
        const float* projection = scene_->camera.matrix();
        std::memcpy(scene_->input.view_projection, projection, sizeof scene_->input.view_projection);
        // A static camera: its view-projection (the projection, world = view) twice.
        std::memcpy(scene_->input.previous_view_projection, projection, sizeof scene_->input.previous_view_projection);
        target_ = make_texture(GL_RGBA8, kWidth, kHeight);
        bent_ = make_texture(GL_RGBA8, kWidth, kHeight);
        blit_target_ = make_renderbuffer_target(GL_RGBA8, kWidth, kHeight);
        ASSERT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
    }
    void TearDown() override {
        FailingGL::reset(-1);
        FailingGL::noise = 0;
        EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
    }

    obscura_context_desc desc() {
        obscura_context_desc d = make_desc(flags_ | GetParam().context_flags);
        d.get_proc_address = nullptr;
        d.get_proc_address_with_user_data = &FailingGL::loader;
        d.allocator.alloc = &FailingGL::host_alloc;
        d.allocator.free = &FailingGL::host_free;
        log_.attach(&d);
        return d;
    }

    std::vector<uint8_t> read_target() {
        if (!GetParam().framebuffer) return read_texture_rgba8(target_.get(), kWidth, kHeight);
        std::vector<uint8_t> bytes(size_t(kWidth) * kHeight * 4);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, blit_target_.framebuffer.get());
        glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        return bytes;
    }

    // Two frames (the first a new history, the second continuing it where the case is temporal), after a prepare if
    // `prepare`, on `context`; stops at the first call that fails.
    Outcome frames(obscura_context* context, bool prepare) {
        const FailureCase& c = GetParam();
        const obscura_settings settings = settings_for(c);
        Outcome outcome;
        auto check = [&](obscura_status status, const char* call) {
            if (status == OBSCURA_OK) return true;
            outcome.status = status;
            outcome.failed_call = call;
            outcome.message = obscura_get_last_error(context);
            return false;
        };
        if (prepare && !check(obscura_prepare(context, kWidth, kHeight, &settings), "obscura_prepare")) return outcome;
        obscura_output output = make_output(c.framebuffer ? 0u : target_.get());
        output.framebuffer = c.framebuffer ? blit_target_.framebuffer.get() : 0u;
        output.bent_normal_texture = c.bent_normals ? bent_.get() : 0u;
        for (uint32_t frame = 0; frame < 2; ++frame) {
            obscura_input input = scene_->input;
            if (!c.temporal) std::memset(input.view_projection, 0, sizeof input.view_projection);
            if (!c.temporal) std::memset(input.previous_view_projection, 0, sizeof input.previous_view_projection);
            input.frame_index = frame;
            input.flags = frame == 0 ? uint32_t(OBSCURA_INPUT_FLAG_RESET_HISTORY) : 0u;
            if (!check(obscura_render(context, &input, &settings, &output), "obscura_render")) return outcome;
        }
        outcome.image = read_target();
        if (c.bent_normals) outcome.bent = read_texture_rgba8(bent_.get(), kWidth, kHeight);
        EXPECT_EQ(obscura_get_memory_usage(context, &outcome.memory), OBSCURA_OK);
        return outcome;
    }

    // Every allocation of creation, (prepare) and two frames made to fail in turn, against a context that never fails.
    void fail_each_allocation(bool prepare) {
        const std::map<std::string, int> objects_before = count_gl_objects();
        const Snapshot state_before = capture();

        FailingGL::reset(-1);
        Outcome clean;
        int allocations = 0;
        {
            obscura_context_desc d = desc();
            obscura_context* raw = nullptr;
            ASSERT_EQ(obscura_create_context(&d, &raw), OBSCURA_OK);
            ContextPtr context(raw);
            clean = frames(context.get(), prepare);
            ASSERT_EQ(clean.status, OBSCURA_OK) << clean.failed_call << ": " << clean.message;
            allocations = FailingGL::allocations;
        }
        // Creation allocates the context (host) and the uniform buffer; the frames the working textures, the method's
        // own, the output's.
        ASSERT_GE(allocations, 4);
        ASSERT_EQ(FailingGL::live_blocks, 0);

        for (int n = 0; n < allocations; ++n) {
            SCOPED_TRACE("allocation " + std::to_string(n) + " of " + std::to_string(allocations) +
                         (prepare ? " (with obscura_prepare)" : ""));
            FailingGL::reset(n);
            obscura_context_desc d = desc();
            obscura_context* raw = nullptr;
            const obscura_status created = obscura_create_context(&d, &raw);
            ContextPtr context(raw);
            if (created != OBSCURA_OK) {
                EXPECT_EQ(created, OBSCURA_STATUS_OUT_OF_MEMORY) << obscura_get_last_error(nullptr);
                EXPECT_EQ(raw, nullptr);
            } else {
                const Outcome failed = frames(context.get(), prepare);
                EXPECT_EQ(failed.status, OBSCURA_STATUS_OUT_OF_MEMORY)
                    << failed.failed_call << ": " << failed.message << " (" << obscura_status_string(failed.status)
                    << ")";
                EXPECT_FALSE(failed.message.empty());
                // The same context, nothing failing: the clean run's frames.
                FailingGL::reset(-1);
                const Outcome again = frames(context.get(), prepare);
                ASSERT_EQ(again.status, OBSCURA_OK) << again.failed_call << ": " << again.message;
                EXPECT_TRUE(again.image == clean.image) << "the image after recovering differs";
                EXPECT_TRUE(again.bent == clean.bent) << "the bent normals after recovering differ";
                EXPECT_EQ(again.memory, clean.memory);
            }
            EXPECT_FALSE(FailingGL::pending) << "GL_OUT_OF_MEMORY (or the error beside it) was never read";
            FailingGL::reset(-1);
            EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
            EXPECT_EQ(diff(state_before, capture()), "");
            context.reset();
            EXPECT_EQ(describe(count_gl_objects()), describe(objects_before)) << "GL objects left behind";
            EXPECT_EQ(FailingGL::live_blocks, 0) << "host allocations left behind";
            if (HasFailure()) return;  // one allocation's report is enough to read
        }
    }

    std::unique_ptr<AoScene> scene_;
    HostTexture target_, bent_;
    RenderbufferTarget blit_target_;
    LogCapture log_;
    uint32_t flags_ = 0;
};

TEST_P(AllocationFailure, EachAllocationOfTheFirstFramesFailsCleanly) { fail_each_allocation(false); }

// With pass validation on, a GL_OUT_OF_MEMORY raised inside a frame is seen at the end of the pass that raised it.
TEST_P(AllocationFailure, EachAllocationOfPrepareFailsCleanlyWithPassValidation) {
    flags_ = OBSCURA_CONTEXT_FLAG_VALIDATE_PASSES;
    fail_each_allocation(true);
}

INSTANTIATE_TEST_SUITE_P(Methods, AllocationFailure, ::testing::ValuesIn(kCases), case_name);

}  // namespace
}  // namespace obscura_test
