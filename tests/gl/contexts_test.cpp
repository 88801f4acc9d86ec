// Context lifetime: several contexts at once (on two GL contexts and on one), resizing, memory
// reporting, GL object and CPU memory leaks, and the timing queries.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "analytic_scene.h"
#include "gl_test_support.h"

namespace obscura_test {
namespace {

// A box on a floor at any size, uploaded as D32F depth on the current GL context.
struct Frame {
    HostTexture depth;
    obscura_input input;
};

Frame box_frame(int width, int height) {
    Camera camera(Projection::Perspective, width, height, Lens(),
                  look_at(glm::dvec3(0.9, 2.4, 3.2), glm::dvec3(0.0, 0.3, 0.0)));
    std::vector<Hit> hits = trace(camera, {plane(1, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0)),
                                           box(2, glm::dvec3(-0.5, 0.0, -0.5), glm::dvec3(0.5, 0.7, 0.5))});
    Frame frame;
    frame.depth = make_depth_texture(GL_DEPTH_COMPONENT32F, width, height, depth_values(camera, hits));
    frame.input = make_input(frame.depth.get(), width, height, camera.matrix(), camera.clip_depth());
    return frame;
}

std::vector<float> render(obscura_context* context, const Frame& frame) {
    return render_to_new_texture(context, frame.input, make_settings(1.0f), GL_R32F, 1);
}

obscura_settings method_defaults(obscura_method method) {
    obscura_settings settings;
    obscura_default_settings(method, &settings);
    return settings;
}

bool identical(const std::vector<float>& a, const std::vector<float>& b) {
    return !a.empty() && a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

bool has_occlusion(const std::vector<float>& v) {
    return !v.empty() && *std::min_element(v.begin(), v.end()) < 0.8f;
}

class Contexts : public GLTest {};

// ---- Several contexts -----------------------------------------------------------------------------------

TEST_F(Contexts, TwoGlContextsRenderAlternately) {
    HeadlessGL& gl_a = shared_gl();
    Frame frame_a = box_frame(96, 64);
    std::vector<float> reference = render(ctx(), frame_a);
    ASSERT_TRUE(has_occlusion(reference));

    HeadlessGL gl_b;  // current now
    ContextPtr ctx_b = create_context();
    ASSERT_NE(ctx_b, nullptr);
    {
        Frame frame_b = box_frame(96, 64);  // a texture of GL context B
        for (int round = 0; round < 3; ++round) {
            gl_a.make_current();
            EXPECT_TRUE(identical(render(ctx(), frame_a), reference)) << "context A, round " << round;
            EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
            gl_b.make_current();
            EXPECT_TRUE(identical(render(ctx_b.get(), frame_b), reference)) << "context B, round " << round;
            EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
        }
        gl_b.make_current();  // frame_b's texture and ctx_b belong to B
    }
    ctx_b.reset();
    gl_a.make_current();
}

TEST_F(Contexts, DestroyWithAnotherGlContextCurrentLeavesThatContextsObjectsAlone) {
    HeadlessGL& gl_a = shared_gl();
    // An obscura context on GL context B, then destroyed while A is current: its names (small integers)
    // also name objects of A, which must survive.
    HeadlessGL gl_b;
    LogCapture log;
    obscura_context_desc desc = make_desc();
    log.attach(&desc);
    obscura_context* on_b = nullptr;
    ASSERT_EQ(obscura_create_context(&desc, &on_b), OBSCURA_OK);
    gl_a.make_current();
    std::vector<GLuint> textures(32), framebuffers(8);
    glGenTextures(GLsizei(textures.size()), textures.data());
    glGenFramebuffers(GLsizei(framebuffers.size()), framebuffers.data());
    for (GLuint t : textures) glBindTexture(GL_TEXTURE_2D, t);
    for (GLuint f : framebuffers) glBindFramebuffer(GL_FRAMEBUFFER, f);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    obscura_destroy_context(on_b);
    for (GLuint t : textures) EXPECT_TRUE(glIsTexture(t)) << "texture " << t << " of context A was deleted";
    for (GLuint f : framebuffers) EXPECT_TRUE(glIsFramebuffer(f)) << "framebuffer " << f << " of A was deleted";
    EXPECT_FALSE(log.entries.empty()) << "the leak must be reported";
    glDeleteTextures(GLsizei(textures.size()), textures.data());
    glDeleteFramebuffers(GLsizei(framebuffers.size()), framebuffers.data());
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(Contexts, ContextOfAnotherGlContextIsRefused) {
    // Both GL contexts hold an obscura context (so both have the same object names): rendering
    // context A while B is current must still be refused, not run with B's objects.
    HeadlessGL& gl_a = shared_gl();
    Frame frame_a = box_frame(96, 64);
    HeadlessGL gl_b;
    ContextPtr ctx_b = create_context();
    ASSERT_NE(ctx_b, nullptr);
    obscura_status status;
    {
        Frame frame_b = box_frame(96, 64);
        std::vector<float> warm = render(ctx_b.get(), frame_b);  // B allocates its resources too
        ASSERT_FALSE(warm.empty());
        HostTexture target = make_texture(GL_R32F, 96, 64);
        obscura_input input = frame_b.input;  // names valid in B
        obscura_output output = make_output(target.get());
        obscura_settings settings = make_settings(1.0f);
        status = obscura_render(ctx(), &input, &settings, &output);
        EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
    }
    ctx_b.reset();
    gl_a.make_current();
    EXPECT_EQ(status, OBSCURA_STATUS_WRONG_GL_CONTEXT) << obscura_get_last_error(ctx());
}

// Timings are GL queries: read with another GL context current they would be that context's names (a GL error
// left in it, or its own timestamps read as ours). Refused, and nothing read, as every call that would touch GL.
TEST_F(Contexts, TimingsOfAnotherGlContextAreRefused) {
    HeadlessGL& gl_a = shared_gl();
    Frame frame = box_frame(96, 64);
    for (int f = 0; f < 4; ++f) ASSERT_FALSE(render(ctx(), frame).empty());  // A's queries exist
    obscura_timing timings[16];
    uint32_t count = 99;
    uint64_t index = 99;
    obscura_status status;
    GLenum error_in_b;
    {
        HeadlessGL gl_b;
        ContextPtr ctx_b = create_context();
        ASSERT_NE(ctx_b, nullptr);
        ASSERT_FALSE(render(ctx_b.get(), box_frame(96, 64)).empty());  // B's queries have A's names
        status = obscura_get_timings(ctx(), timings, 16, &count, &index);
        error_in_b = take_gl_error();
        ctx_b.reset();
    }
    gl_a.make_current();
    EXPECT_EQ(status, OBSCURA_STATUS_WRONG_GL_CONTEXT) << obscura_get_last_error(ctx());
    EXPECT_EQ(error_in_b, GLenum(GL_NO_ERROR));
    EXPECT_EQ(count, 0u);
    EXPECT_EQ(index, 0u);
    EXPECT_EQ(obscura_get_timings(ctx(), timings, 16, &count, &index), OBSCURA_OK) << "A's own context again";
}

TEST_F(Contexts, TwoContextsOnOneGlContext) {
    Frame frame = box_frame(96, 64);
    std::vector<float> reference = render(ctx(), frame);
    ASSERT_TRUE(has_occlusion(reference));
    ContextPtr second = create_context();
    ASSERT_NE(second, nullptr);
    Frame other_size = box_frame(64, 48);
    std::vector<float> other_reference = render(second.get(), other_size);
    for (int round = 0; round < 3; ++round) {
        EXPECT_TRUE(identical(render(ctx(), frame), reference)) << round;
        EXPECT_TRUE(identical(render(second.get(), other_size), other_reference)) << round;
    }
    second.reset();  // destroying one leaves the other working
    EXPECT_TRUE(identical(render(ctx(), frame), reference));
}

// ---- Resizing and memory -------------------------------------------------------------------------------

TEST_F(Contexts, ResizeRoundTrip) {
    Frame small = box_frame(96, 64);
    Frame large = box_frame(160, 90);
    uint64_t idle = 0, m_small = 0, m_large = 0, m_small_again = 0;
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &idle), OBSCURA_OK);
    std::vector<float> first = render(ctx(), small);
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &m_small), OBSCURA_OK);
    std::vector<float> big = render(ctx(), large);
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &m_large), OBSCURA_OK);
    std::vector<float> again = render(ctx(), small);
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &m_small_again), OBSCURA_OK);
    EXPECT_TRUE(has_occlusion(big));
    EXPECT_TRUE(identical(first, again)) << "the same frame after a resize round trip";
    EXPECT_EQ(m_small, m_small_again);
    EXPECT_GT(m_small, idle);
    EXPECT_GT(m_large, m_small);
    // Per-size resources scale with the texel count.
    double per_texel_small = double(m_small - idle) / (96 * 64);
    double per_texel_large = double(m_large - idle) / (160 * 90);
    EXPECT_DOUBLE_EQ(per_texel_small, per_texel_large);
    EXPECT_GE(per_texel_small, 8.0) << "at least linear depth (R32F) and normals";
}

TEST_F(Contexts, ReleaseResourcesReturnsToIdle) {
    uint64_t idle = 0, used = 0, released = 0;
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &idle), OBSCURA_OK);
    Frame frame = box_frame(96, 64);
    std::vector<float> before = render(ctx(), frame);
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &used), OBSCURA_OK);
    obscura_release_resources(ctx());
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &released), OBSCURA_OK);
    EXPECT_GT(used, idle);
    EXPECT_EQ(released, idle);
    EXPECT_TRUE(identical(render(ctx(), frame), before)) << "resources are recreated on the next render";
}

// The context holds the shared working textures its configuration's passes use and nothing else (obscura.h,
// obscura_get_memory_usage). Until 2026-12-06 every configuration held the AO pass's R16F result, and every one
// with a reconstruction its intermediate and its result: SAO, whose passes use packed textures of their own, held
// all three for nothing, and since the methods' last passes write the host's target at full resolution nothing read
// the result texture there either.
TEST_F(Contexts, MemoryHoldsOnlyTheWorkingTexturesItsPassesUse) {
    Frame frame = box_frame(96, 64);
    const uint64_t texels = uint64_t(frame.input.depth_width) * uint64_t(frame.input.depth_height);
    auto bytes_after = [&](const obscura_settings& settings) {
        EXPECT_FALSE(render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1).empty());
        uint64_t bytes = 0;
        EXPECT_EQ(obscura_get_memory_usage(ctx(), &bytes), OBSCURA_OK);
        return bytes;
    };
    obscura_settings hbao = method_defaults(OBSCURA_METHOD_HBAO), hbao_plain = hbao, hbao_temporal = hbao;
    hbao_plain.hbao.blur = OBSCURA_TOGGLE_OFF;
    hbao_temporal.temporal.enabled = OBSCURA_TOGGLE_ON;
    obscura_settings sao = method_defaults(OBSCURA_METHOD_SAO), sao_plain = sao;
    sao_plain.sao.blur = OBSCURA_TOGGLE_OFF;
    const uint64_t hbao_bytes = bytes_after(hbao), hbao_plain_bytes = bytes_after(hbao_plain);
    const uint64_t hbao_temporal_bytes = bytes_after(hbao_temporal);
    const uint64_t sao_bytes = bytes_after(sao), sao_plain_bytes = bytes_after(sao_plain);
    // The blur's intermediate (R16F) alone: its vertical pass writes the host's target.
    EXPECT_EQ(hbao_bytes - hbao_plain_bytes, texels * 2);
    // With accumulation the blur's result is the temporal pass's source (R16F), besides the view's history.
    EXPECT_GT(hbao_temporal_bytes, hbao_bytes + texels * 2);
    // SAO uses none of the shared AO textures; without its blur it keeps no packed intermediate (RGBA8) either.
    EXPECT_EQ(sao_bytes - sao_plain_bytes, texels * 4);
    EXPECT_EQ(bytes_after(hbao), hbao_bytes) << "the same configuration reports the same bytes";
}

TEST_F(Contexts, PrepareAllocatesWhatRenderUses) {
    uint64_t prepared = 0, rendered = 0;
    obscura_settings settings = make_settings(1.0f);
    ASSERT_EQ(obscura_prepare(ctx(), 96, 64, &settings), OBSCURA_OK);
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &prepared), OBSCURA_OK);
    Frame frame = box_frame(96, 64);
    ASSERT_FALSE(render(ctx(), frame).empty());
    ASSERT_EQ(obscura_get_memory_usage(ctx(), &rendered), OBSCURA_OK);
    EXPECT_EQ(prepared, rendered);
}

// ---- Leaks ---------------------------------------------------------------------------------------------

// One full use of a context: resize, every output kind, then destroy.
void exercise_context(uint32_t flags) {
    ContextPtr context = create_context(flags);
    ASSERT_NE(context, nullptr);
    Frame small = box_frame(96, 64);
    Frame large = box_frame(160, 90);
    ASSERT_FALSE(render(context.get(), small).empty());
    ASSERT_FALSE(render(context.get(), large).empty());
    HostRenderbuffer renderbuffer = HostRenderbuffer::create();
    glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer.get());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 96, 64);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    HostFramebuffer framebuffer = HostFramebuffer::create();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffer.get());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    obscura_output output = make_output(0);
    output.framebuffer = framebuffer.get();
    output.blend = OBSCURA_BLEND_MULTIPLY;
    obscura_settings settings = make_settings(1.0f);
    ASSERT_EQ(obscura_render(context.get(), &small.input, &settings, &output), OBSCURA_OK);
    for (GLenum format : {GL_RGBA8, GL_R16F, GL_RG32F}) {
        HostTexture target = make_texture(format, 96, 64);
        obscura_output to_texture = make_output(target.get(), OBSCURA_DEBUG_NORMALS);
        ASSERT_EQ(obscura_render(context.get(), &small.input, &settings, &to_texture), OBSCURA_OK);
    }
    ASSERT_EQ(obscura_prepare(context.get(), 200, 100, &settings), OBSCURA_OK);
    context.reset();
}

TEST_F(Contexts, NoGlObjectsLeak) {
    glFinish();
    std::map<std::string, int> before = count_gl_objects();
    for (int cycle = 0; cycle < 3; ++cycle) {
        exercise_context(0);
        exercise_context(OBSCURA_CONTEXT_FLAG_SYNC_TIMING);
        if (HasFatalFailure()) return;
    }
    std::map<std::string, int> after = count_gl_objects();
    EXPECT_EQ(before, after) << "before: " << describe(before) << "\nafter:  " << describe(after);
}

TEST_F(Contexts, ObjectScanSeesLiveContexts) {
    std::map<std::string, int> before = count_gl_objects();
    ContextPtr context = create_context();
    Frame frame = box_frame(96, 64);
    ASSERT_FALSE(render(context.get(), frame).empty());
    std::map<std::string, int> alive = count_gl_objects();
    EXPECT_GE(alive["texture"], before["texture"] + 1 + 4)
        << "the host depth/target plus >= 4 working textures (linear depth, normals, the AO, the blur's intermediate)";
    EXPECT_GT(alive["program"], before["program"]);
    EXPECT_GT(alive["sampler"], before["sampler"]);
    EXPECT_GT(alive["buffer"], before["buffer"]);
    EXPECT_GT(alive["query"], before["query"]);
}

// Counts the CPU allocations a context makes through the host allocator.
struct CountingAllocator {
    long long live_blocks = 0;
    long long total_blocks = 0;
    long long live_bytes = 0;
    // Each block carries its size in front (as much room as malloc's alignment, which the SDK relies on).
    static constexpr size_t kHeader = alignof(std::max_align_t);
    static void* alloc(size_t size, void* user) {
        auto* self = static_cast<CountingAllocator*>(user);
        auto* block = static_cast<unsigned char*>(std::malloc(size + kHeader));
        if (!block) return nullptr;
        std::memcpy(block, &size, sizeof size);
        ++self->live_blocks;
        ++self->total_blocks;
        self->live_bytes += static_cast<long long>(size);
        return block + kHeader;
    }
    static void release(void* ptr, void* user) {
        if (!ptr) return;
        auto* self = static_cast<CountingAllocator*>(user);
        unsigned char* block = static_cast<unsigned char*>(ptr) - kHeader;
        size_t size = 0;
        std::memcpy(&size, block, sizeof size);
        --self->live_blocks;
        self->live_bytes -= static_cast<long long>(size);
        std::free(block);
    }
    void attach(obscura_context_desc* desc) {
        desc->allocator.alloc = &CountingAllocator::alloc;
        desc->allocator.free = &CountingAllocator::release;
        desc->allocator.user_data = this;
    }
};

TEST_F(Contexts, HostAllocatorBalanced) {
    CountingAllocator counter;
    obscura_context_desc desc = make_desc();
    counter.attach(&desc);
    obscura_context* context = nullptr;
    ASSERT_EQ(obscura_create_context(&desc, &context), OBSCURA_OK);
    EXPECT_GE(counter.live_blocks, 1) << "the context itself lives in host-allocated memory";
    Frame frame = box_frame(96, 64);
    EXPECT_FALSE(render(context, frame).empty());
    obscura_destroy_context(context);
    EXPECT_EQ(counter.live_blocks, 0) << "of " << counter.total_blocks << " allocations";
    EXPECT_GT(counter.total_blocks, 1) << "shader assembly goes through the allocator too";
}

// LSAO's and FFAO's line layouts (kept per layout phase, megabytes at 4K) are the context's largest CPU memory: they
// live in the host allocator's memory, and obscura_release_resources gives them back. At 320x180 each layout holds a
// line record per line (hundreds per direction); they once came from the C++ heap, unseen by the allocator.
TEST_F(Contexts, HostAllocatorHoldsTheLineLayouts) {
    const Frame frame = box_frame(320, 180);
    for (obscura_method method : {OBSCURA_METHOD_LSAO, OBSCURA_METHOD_FFAO}) {
        SCOPED_TRACE(method == OBSCURA_METHOD_LSAO ? "LSAO" : "FFAO");
        CountingAllocator counter;
        obscura_context_desc desc = make_desc();
        counter.attach(&desc);
        obscura_context* raw = nullptr;
        ASSERT_EQ(obscura_create_context(&desc, &raw), OBSCURA_OK);
        ContextPtr context(raw);
        const obscura_settings settings = method_defaults(method);
        EXPECT_FALSE(render_to_new_texture(context.get(), frame.input, settings, GL_R32F, 1).empty());
        const long long rendered = counter.live_bytes;
        obscura_release_resources(context.get());
        const long long released = counter.live_bytes;
        // Every direction's lines across the 352x198 texture (guard band included), 16 bytes or more a line.
        EXPECT_GT(rendered - released, 16 * 1024) << rendered << " bytes live after a frame, " << released
                                                  << " after release";
        context.reset();
        EXPECT_EQ(counter.live_blocks, 0);
        EXPECT_EQ(counter.live_bytes, 0);
    }
}

// A tuning session sweeps the settings that are compiled in (GTAO's slices and steps): the context keeps the last
// few programs of each pass, not one per value it ever ran.
TEST_F(Contexts, CompiledVariantsAreBoundedWhenASettingIsSwept) {
    const Frame frame = box_frame(48, 32);
    obscura_settings settings = method_defaults(OBSCURA_METHOD_GTAO);
    settings.gtao.slices = 1;
    EXPECT_FALSE(render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1).empty());
    const int first = count_gl_objects()["program"];
    for (int slices = 2; slices <= 12; ++slices) {
        settings.gtao.slices = slices;
        EXPECT_FALSE(render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1).empty());
    }
    // 12 variants rendered; the pass keeps 8 of them.
    EXPECT_EQ(count_gl_objects()["program"], first + 7);
    // The latest one is still there: rendering it again compiles nothing.
    EXPECT_FALSE(render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1).empty());
    EXPECT_EQ(count_gl_objects()["program"], first + 7);
}

// A host rendering several configurations of one method every frame (here five GTAO variants, views with their own
// settings) compiles each once: the pass keeps them all, and the second round builds no program.
TEST_F(Contexts, SeveralVariantsAFrameAreCompiledOnce) {
    const Frame frame = box_frame(48, 32);
    obscura_settings settings = method_defaults(OBSCURA_METHOD_GTAO);
    auto render_variants = [&] {
        for (int slices = 1; slices <= 5; ++slices) {
            settings.gtao.slices = slices;
            EXPECT_FALSE(render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1).empty());
        }
    };
    settings.gtao.slices = 5;
    EXPECT_FALSE(render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1).empty());  // the other passes' too
    const int first = count_gl_objects()["program"];
    render_variants();
    EXPECT_EQ(count_gl_objects()["program"], first + 4) << "every variant kept";
    render_variants();
    EXPECT_EQ(count_gl_objects()["program"], first + 4);
}

// ---- Timings ---------------------------------------------------------------------------------------------

class SyncTimings : public GLTest {
protected:
    SyncTimings() { context_flags_ = OBSCURA_CONTEXT_FLAG_SYNC_TIMING; }
};

// The labels of `count` timings (at most kTimingCapacity, what the tests read).
constexpr uint32_t kTimingCapacity = 16;
std::vector<std::string> labels_of(const obscura_timing* timings, uint32_t count) {
    std::vector<std::string> labels;
    for (uint32_t i = 0; i < std::min(count, kTimingCapacity); ++i)
        labels.push_back(timings[i].label ? timings[i].label : "(null)");
    return labels;
}

// What every complete result holds, whatever the clock behind it reads (GL timer queries may read 0 on
// llvmpipe): each value finite and >= 0, and the total no less than its largest pass.
void expect_valid_values(const obscura_timing* timings, uint32_t count) {
    ASSERT_GT(count, 0u);
    double largest_pass = 0.0;
    for (uint32_t i = 0; i < std::min(count, kTimingCapacity); ++i) {
        const char* label = timings[i].label ? timings[i].label : "(null)";
        EXPECT_TRUE(std::isfinite(timings[i].milliseconds)) << label << ": " << timings[i].milliseconds;
        EXPECT_GE(timings[i].milliseconds, 0.0) << label;
        if (i > 0) largest_pass = std::max(largest_pass, timings[i].milliseconds);
    }
    EXPECT_GE(timings[0].milliseconds, largest_pass) << "the total is less than one of its passes";
}

// With sync timing a frame's timings are there the moment obscura_render returns, and they name exactly the
// passes that method and those settings run (obscura.h, obscura_timing.label), in the order they ran. The cases
// share one context, in this order: FFAO builds its falloff table on its first frame and again only when the
// falloff's shape changes.
TEST_F(SyncTimings, AtOnceAfterRenderWithExactlyTheMethodsPasses) {
    struct Case {
        const char* what;
        obscura_settings settings;
        std::vector<std::string> passes;  // after "total"
    };
    obscura_settings hbao = make_settings(1.0f);
    hbao.hbao.blur = OBSCURA_TOGGLE_ON;
    obscura_settings hbao_no_blur = hbao;
    hbao_no_blur.hbao.blur = OBSCURA_TOGGLE_OFF;
    obscura_settings reference = method_defaults(OBSCURA_METHOD_REFERENCE);
    reference.reference.rays = 16;
    obscura_settings sao = method_defaults(OBSCURA_METHOD_SAO);
    sao.sao.blur = OBSCURA_TOGGLE_ON;
    obscura_settings sao_no_blur = sao;
    sao_no_blur.sao.blur = OBSCURA_TOGGLE_OFF;
    obscura_settings lsao = method_defaults(OBSCURA_METHOD_LSAO);
    obscura_settings ffao = method_defaults(OBSCURA_METHOD_FFAO);
    // The infinitely thick field (thickness 0): its scanned peaks are summed over sectors (the prefix pass); with a
    // thickness (the default) single lines are read and there is no prefix pass.
    ffao.ffao.thickness = 0.0f;
    obscura_settings ffao_thick = method_defaults(OBSCURA_METHOD_FFAO);
    ffao.ffao.saao = OBSCURA_TOGGLE_OFF;
    obscura_settings ffao_saao = ffao;
    ffao_saao.ffao.saao = OBSCURA_TOGGLE_ON;
    ffao_saao.ffao.sectors = 18;  // SAAO needs K = 18n
    ffao_saao.ffao.saao_blur = OBSCURA_TOGGLE_ON;
    obscura_settings ffao_rho0 = ffao;
    ffao_rho0.ffao.falloff = OBSCURA_FALLOFF_RHO0;
    obscura_settings gtao = method_defaults(OBSCURA_METHOD_GTAO);
    obscura_settings gtao_no_denoise = gtao;
    gtao_no_denoise.gtao.denoise = OBSCURA_TOGGLE_OFF;
    obscura_settings hbao_temporal = hbao;
    hbao_temporal.temporal.enabled = OBSCURA_TOGGLE_ON;
    obscura_settings gtao_temporal = method_defaults(OBSCURA_METHOD_GTAO);
    gtao_temporal.temporal.enabled = OBSCURA_TOGGLE_ON;
    obscura_settings hbao_half = hbao;
    hbao_half.resolution.scale = OBSCURA_RESOLUTION_HALF;
    obscura_settings gtao_quarter_temporal = gtao_temporal;
    gtao_quarter_temporal.resolution.scale = OBSCURA_RESOLUTION_QUARTER;
    const Case cases[] = {
        // The last reconstruction pass writes the target itself (full resolution, no accumulation): no composite.
        {"hbao, blur", hbao, {"depth_prepare", "hbao", "blur"}},
        {"hbao, no blur", hbao_no_blur, {"depth_prepare", "hbao", "composite"}},
        {"reference", reference, {"depth_prepare", "reference", "composite"}},
        {"sao, blur", sao, {"depth_prepare", "z_pyramid", "sao", "blur"}},
        {"sao, no blur", sao_no_blur, {"depth_prepare", "z_pyramid", "sao", "composite"}},
        {"lsao", lsao, {"depth_prepare", "line_sweep", "gather"}},
        {"gtao", gtao, {"depth_prepare", "z_pyramid", "gtao", "gtao_denoise"}},
        {"gtao, no denoise", gtao_no_denoise, {"depth_prepare", "z_pyramid", "gtao", "composite"}},
        {"ffao, first frame: builds the table",
         ffao,
         {"depth_prepare", "ffao_table", "ffao_scan", "ffao_prefix", "ffao_obscurance", "composite"}},
        {"ffao, same falloff: keeps the table",
         ffao,
         {"depth_prepare", "ffao_scan", "ffao_prefix", "ffao_obscurance", "composite"}},
        {"ffao saao, same falloff",
         ffao_saao,
         {"depth_prepare", "ffao_box_average", "ffao_scan", "ffao_prefix", "ffao_obscurance", "ffao_gather", "blur",
          "composite"}},
        {"ffao, default thickness: single lines, no prefix sums",
         ffao_thick,
         {"depth_prepare", "ffao_scan", "ffao_obscurance", "composite"}},
        {"ffao, another falloff shape: a new table",
         ffao_rho0,
         {"depth_prepare", "ffao_table", "ffao_scan", "ffao_prefix", "ffao_obscurance", "composite"}},
        // At full resolution the temporal pass writes the target itself: no composite.
        {"hbao, temporal", hbao_temporal, {"depth_prepare", "hbao", "blur", "temporal"}},
        {"gtao, temporal", gtao_temporal, {"depth_prepare", "z_pyramid", "gtao", "gtao_denoise", "temporal"}},
        // At reduced resolution the upsample writes the target itself: no composite.
        {"hbao, half resolution", hbao_half, {"depth_prepare", "hbao", "blur", "upsample"}},
        {"gtao, temporal, quarter resolution",
         gtao_quarter_temporal,
         {"depth_prepare", "z_pyramid", "gtao", "gtao_denoise", "temporal", "upsample"}},
    };
    Frame frame = box_frame(96, 64);
    uint64_t renders = 0;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        ASSERT_FALSE(render_to_new_texture(ctx(), frame.input, c.settings, GL_R32F, 1).empty());
        ++renders;
        obscura_timing timings[kTimingCapacity] = {};
        uint32_t count = 0;
        uint64_t frame_index = 0;
        ASSERT_EQ(obscura_get_timings(ctx(), timings, kTimingCapacity, &count, &frame_index), OBSCURA_OK);
        ASSERT_GT(count, 0u) << "sync timing has the frame's timings as soon as obscura_render returns";
        EXPECT_EQ(frame_index, renders) << "the timings belong to the frame just rendered";
        std::vector<std::string> expected = {"total"};
        expected.insert(expected.end(), c.passes.begin(), c.passes.end());
        EXPECT_EQ(labels_of(timings, count), expected);
        expect_valid_values(timings, count);
        EXPECT_GT(timings[0].milliseconds, 0.0) << "glFinish-timed work cannot take zero time";
    }
}

// FFAO's estimator table depends on the falloff's shape alone: a resize keeps it (until 2026-12-06 every resized frame
// rebuilt it, a 3D texture allocation and the ffao_table pass for a host resizing its window each frame);
// obscura_release_resources frees it.
TEST_F(SyncTimings, FfaoKeepsItsTableAcrossAResize) {
    obscura_settings ffao = method_defaults(OBSCURA_METHOD_FFAO);
    const auto builds_table = [&](const Frame& frame) {
        EXPECT_FALSE(render_to_new_texture(ctx(), frame.input, ffao, GL_R32F, 1).empty());
        obscura_timing timings[kTimingCapacity] = {};
        uint32_t count = 0;
        EXPECT_EQ(obscura_get_timings(ctx(), timings, kTimingCapacity, &count, nullptr), OBSCURA_OK);
        const std::vector<std::string> labels = labels_of(timings, count);
        EXPECT_GT(labels.size(), 2u);
        return std::find(labels.begin(), labels.end(), "ffao_table") != labels.end();
    };
    const Frame small = box_frame(96, 64), large = box_frame(128, 72);
    EXPECT_TRUE(builds_table(small));
    EXPECT_FALSE(builds_table(large)) << "a resize rebuilt the table";
    EXPECT_FALSE(builds_table(small));
    obscura_release_resources(ctx());
    EXPECT_TRUE(builds_table(small)) << "released resources must include the table";
}

TEST_F(SyncTimings, NoBlurPassWithoutBlur) {
    Frame frame = box_frame(96, 64);
    obscura_settings settings = make_settings(1.0f);
    settings.hbao.blur = OBSCURA_TOGGLE_OFF;
    ASSERT_FALSE(render_to_new_texture(ctx(), frame.input, settings, GL_R32F, 1).empty());
    obscura_timing timings[8] = {};
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_timings(ctx(), timings, 8, &count, nullptr), OBSCURA_OK);
    ASSERT_EQ(count, 4u);
    EXPECT_STREQ(timings[0].label, "total");
    EXPECT_STREQ(timings[1].label, "depth_prepare");
    EXPECT_STREQ(timings[2].label, "hbao");
    EXPECT_STREQ(timings[3].label, "composite");
}

TEST_F(SyncTimings, SmallCapacityReportsAvailableCount) {
    Frame frame = box_frame(96, 64);
    ASSERT_FALSE(render(ctx(), frame).empty());
    obscura_timing timings[3];
    timings[2].label = "untouched";
    timings[2].milliseconds = -7.0;
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_timings(ctx(), timings, 2, &count, nullptr), OBSCURA_OK);
    EXPECT_EQ(count, 4u);
    EXPECT_STREQ(timings[0].label, "total");
    EXPECT_STREQ(timings[1].label, "depth_prepare");
    EXPECT_STREQ(timings[2].label, "untouched");
    EXPECT_EQ(timings[2].milliseconds, -7.0);
    ASSERT_EQ(obscura_get_timings(ctx(), nullptr, 0, &count, nullptr), OBSCURA_OK);
    EXPECT_EQ(count, 4u);
}

TEST_F(SyncTimings, NothingBeforeTheFirstFrame) {
    obscura_timing timings[8];
    uint32_t count = 99;
    ASSERT_EQ(obscura_get_timings(ctx(), timings, 8, &count, nullptr), OBSCURA_OK);
    EXPECT_EQ(count, 0u);
}

TEST_F(Contexts, GpuTimingsNeverBlockAndArrive) {
    // Without SYNC_TIMING the timer-query results of a frame are read only once available: every call returns at
    // once, with nothing until a frame's queries have completed, then "total" and that frame's passes. With
    // glFinish after every frame a result must arrive within a few frames (the ring holds 4 in flight).
    constexpr int kMaxFrames = 16;
    const std::vector<std::string> expected = {"total", "depth_prepare", "hbao", "blur"};
    Frame frame = box_frame(96, 64);
    int renders = 0;
    bool arrived = false;
    while (!arrived && renders < kMaxFrames) {
        ASSERT_FALSE(render(ctx(), frame).empty());
        ++renders;
        glFinish();
        obscura_timing timings[kTimingCapacity] = {};
        uint32_t count = 99;
        uint64_t frame_index = 99;
        auto start = std::chrono::steady_clock::now();
        ASSERT_EQ(obscura_get_timings(ctx(), timings, kTimingCapacity, &count, &frame_index), OBSCURA_OK);
        double call_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        EXPECT_LT(call_ms, 50.0) << "obscura_get_timings must not wait for the GPU";
        if (count == 0) {
            EXPECT_EQ(frame_index, 0u) << "no result yet, after " << renders << " frames";
            continue;
        }
        arrived = true;
        EXPECT_GE(frame_index, 1u);
        EXPECT_LE(frame_index, uint64_t(renders)) << "a result for a frame not yet rendered";
        EXPECT_EQ(labels_of(timings, count), expected);
        expect_valid_values(timings, count);
    }
    ASSERT_TRUE(arrived) << "no frame's timings arrived within " << kMaxFrames << " frames, with glFinish after each";
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

// The timer reads a query's result only once GL says it is available (a read before would wait for the GPU): a
// loader that answers "not available" must get no result read, and the frame's timings then arrive once it answers
// the truth. (Under llvmpipe, queries complete at glFinish: the stand-in is what makes "never block" observable.)
struct PendingQueries {
    static bool pending;
    static int result_reads;
    static void (*real_get_uiv)(GLuint, GLenum, GLuint*);
    static void (*real_get_ui64v)(GLuint, GLenum, GLuint64*);
    static void GLAD_API_PTR get_uiv(GLuint query, GLenum name, GLuint* value) {
        real_get_uiv(query, name, value);
        if (name == GL_QUERY_RESULT_AVAILABLE && pending) *value = GL_FALSE;
    }
    static void GLAD_API_PTR get_ui64v(GLuint query, GLenum name, GLuint64* value) {
        if (name == GL_QUERY_RESULT) ++result_reads;
        real_get_ui64v(query, name, value);
    }
    static obscura_gl_function loader(void*, const char* name) {
        if (std::strcmp(name, "glGetQueryObjectuiv") == 0) return reinterpret_cast<obscura_gl_function>(&get_uiv);
        if (std::strcmp(name, "glGetQueryObjectui64v") == 0) return reinterpret_cast<obscura_gl_function>(&get_ui64v);
        return obscura::samples::HeadlessGL::get_proc_address(name);
    }
};
bool PendingQueries::pending = false;
int PendingQueries::result_reads = 0;
void (*PendingQueries::real_get_uiv)(GLuint, GLenum, GLuint*) = nullptr;
void (*PendingQueries::real_get_ui64v)(GLuint, GLenum, GLuint64*) = nullptr;

TEST_F(Contexts, GpuTimingsReadNoQueryBeforeItIsAvailable) {
    PendingQueries::real_get_uiv = reinterpret_cast<void (*)(GLuint, GLenum, GLuint*)>(
        obscura::samples::HeadlessGL::get_proc_address("glGetQueryObjectuiv"));
    PendingQueries::real_get_ui64v = reinterpret_cast<void (*)(GLuint, GLenum, GLuint64*)>(
        obscura::samples::HeadlessGL::get_proc_address("glGetQueryObjectui64v"));
    obscura_context_desc desc = make_desc();
    desc.get_proc_address = nullptr;
    desc.get_proc_address_with_user_data = &PendingQueries::loader;
    obscura_context* raw = nullptr;
    ASSERT_EQ(obscura_create_context(&desc, &raw), OBSCURA_OK);
    ContextPtr context(raw);
    Frame frame = box_frame(96, 64);
    PendingQueries::pending = true;
    PendingQueries::result_reads = 0;
    for (int i = 0; i < 8; ++i) {
        ASSERT_FALSE(render(context.get(), frame).empty());
        glFinish();
        uint32_t count = 99;
        ASSERT_EQ(obscura_get_timings(context.get(), nullptr, 0, &count, nullptr), OBSCURA_OK);
        EXPECT_EQ(count, 0u) << "a result of a query GL called unavailable, frame " << i;
    }
    EXPECT_EQ(PendingQueries::result_reads, 0) << "query results read before they were available (a stall on a GPU)";
    PendingQueries::pending = false;
    ASSERT_FALSE(render(context.get(), frame).empty());
    glFinish();
    obscura_timing timings[kTimingCapacity] = {};
    uint32_t count = 0;
    ASSERT_EQ(obscura_get_timings(context.get(), timings, kTimingCapacity, &count, nullptr), OBSCURA_OK);
    EXPECT_GT(count, 0u) << "the timings must arrive once the queries are available";
    EXPECT_GT(PendingQueries::result_reads, 0);
    EXPECT_EQ(take_gl_error(), GLenum(GL_NO_ERROR));
}

TEST_F(SyncTimings, FrameIndexCountsRendersAndZeroBeforeAny) {
    obscura_timing timings[8] = {};
    uint32_t count = 0;
    uint64_t frame_index = 99;
    ASSERT_EQ(obscura_get_timings(ctx(), timings, 8, &count, &frame_index), OBSCURA_OK);
    EXPECT_EQ(count, 0u);
    EXPECT_EQ(frame_index, 0u) << "no frame has completed yet";
    Frame frame = box_frame(96, 64);
    ASSERT_FALSE(render(ctx(), frame).empty());
    ASSERT_EQ(obscura_get_timings(ctx(), timings, 8, &count, &frame_index), OBSCURA_OK);
    EXPECT_EQ(frame_index, 1u);
    ASSERT_FALSE(render(ctx(), frame).empty());
    ASSERT_EQ(obscura_get_timings(ctx(), timings, 8, &count, &frame_index), OBSCURA_OK);
    EXPECT_EQ(frame_index, 2u) << "sync timing reports the frame just rendered";
}

// A stateful loader: counts its lookups through the user pointer.
obscura_gl_function counting_loader(void* user_data, const char* name) {
    ++*static_cast<int*>(user_data);
    return HeadlessGL::get_proc_address(name);
}

TEST(LoaderCallbacks, UserDataLoaderIsUsedAndRenders) {
    shared_gl().make_current();
    int lookups = 0;
    obscura_context_desc desc = make_desc();
    desc.get_proc_address = nullptr;
    desc.get_proc_address_with_user_data = &counting_loader;
    desc.get_proc_address_user_data = &lookups;
    obscura_context* raw = nullptr;
    ASSERT_EQ(obscura_create_context(&desc, &raw), OBSCURA_OK);
    ContextPtr context(raw);
    EXPECT_GT(lookups, 100) << "the whole GL 4.3 table is loaded through the user-data loader";
    Frame frame = box_frame(96, 64);
    EXPECT_FALSE(render(context.get(), frame).empty());
}

TEST(LoaderCallbacks, BothOrNeitherLoaderIsRejected) {
    shared_gl().make_current();
    int lookups = 0;
    obscura_context_desc desc = make_desc();
    desc.get_proc_address_with_user_data = &counting_loader;
    desc.get_proc_address_user_data = &lookups;
    obscura_context* raw = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &raw), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(raw, nullptr);
    desc.get_proc_address = nullptr;
    desc.get_proc_address_with_user_data = nullptr;
    EXPECT_EQ(obscura_create_context(&desc, &raw), OBSCURA_STATUS_NULL_ARGUMENT);
    EXPECT_EQ(lookups, 0) << "a rejected desc must not touch GL";
}

}  // namespace
}  // namespace obscura_test
