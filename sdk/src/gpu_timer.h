// Per-pass GPU timings without stalls: a ring of timestamp queries, one set per frame in flight.
// A frame's results are read only once its last query is available, so reading never waits; until
// then the previous complete frame's timings are reported. With sync timing (benchmarks on drivers
// whose timer queries read 0) every mark calls glFinish and reads the CPU clock instead.
#ifndef OBSCURA_GPU_TIMER_H
#define OBSCURA_GPU_TIMER_H

#include <chrono>

#include "gl/gl_objects.h"
#include "obscura/obscura.h"
#include "pass_id.h"

namespace obscura {

class GpuTimer {
public:
    static constexpr int kFramesInFlight = 4;
    static constexpr int kMaxPasses = 32;  // marks per frame (FFAO in chunks marks each chunk's passes)

    // `query_buffers`: the context has GL_QUERY_BUFFER (GL 4.4 or ARB_query_buffer_object), whose host binding the
    // timer sets aside while it reads its queries.
    void create(const gl::Table& gl, bool sync_timing, bool query_buffers);
    void destroy();

    // Frame bracketing: each mark ends the pass it names.
    void begin_frame();
    void mark(PassId pass);
    void end_frame();

    // Latest complete frame: "total" first, then each pass, once (a pass marked several times in a frame, as FFAO's
    // chunks are, reports the sum, where its first mark was). Returns the number available and sets
    // *frame_index to that frame's 1-based index among the frames begun (0 when none completed yet).
    uint32_t latest(obscura_timing* out, uint32_t capacity, uint64_t* frame_index);

private:
    struct FrameSlot {
        gl::Object queries[kMaxPasses + 1];
        PassId passes[kMaxPasses] = {};
        int marks = 0;
        bool pending = false;
        uint64_t frame_index = 0;
    };
    void collect();

    const gl::Table* gl_ = nullptr;
    bool sync_ = false;
    bool query_buffers_ = false;
    FrameSlot slots_[kFramesInFlight];
    int current_ = -1;  // slot being recorded, -1 when this frame is not timed
    int next_ = 0;
    std::chrono::steady_clock::time_point sync_last_;
    PassId latest_passes_[kMaxPasses] = {};
    double latest_ms_[kMaxPasses] = {};
    int latest_count_ = 0;
    uint64_t latest_frame_ = 0;
    uint64_t frames_begun_ = 0;
    int sync_count_ = 0;
    PassId sync_passes_[kMaxPasses] = {};
    double sync_ms_[kMaxPasses] = {};
};

}  // namespace obscura

#endif  // OBSCURA_GPU_TIMER_H
