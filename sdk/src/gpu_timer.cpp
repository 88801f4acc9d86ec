#include "gpu_timer.h"

namespace obscura {

void GpuTimer::create(const gl::Table& gl, bool sync_timing, bool query_buffers) {
    gl_ = &gl;
    sync_ = sync_timing;
    query_buffers_ = query_buffers;
    if (sync_) return;
    for (FrameSlot& slot : slots_)
        for (gl::Object& query : slot.queries) query = gl::create_query(gl);
}

void GpuTimer::destroy() {
    for (FrameSlot& slot : slots_)
        for (gl::Object& query : slot.queries) query.reset();
}

void GpuTimer::begin_frame() {
    ++frames_begun_;
    if (sync_) {
        gl_->Finish();
        sync_last_ = std::chrono::steady_clock::now();
        sync_count_ = 0;
        return;
    }
    collect();
    current_ = -1;
    FrameSlot& slot = slots_[next_];
    if (slot.pending) return;  // all slots still in flight: skip timing this frame rather than wait
    current_ = next_;
    next_ = (next_ + 1) % kFramesInFlight;
    slot.marks = 0;
    slot.frame_index = frames_begun_;
    gl_->QueryCounter(slot.queries[0].name(), GL_TIMESTAMP);
}

void GpuTimer::mark(PassId pass) {
    if (sync_) {
        gl_->Finish();
        auto now = std::chrono::steady_clock::now();
        if (sync_count_ < kMaxPasses) {
            sync_passes_[sync_count_] = pass;
            sync_ms_[sync_count_] = std::chrono::duration<double, std::milli>(now - sync_last_).count();
            ++sync_count_;
        }
        sync_last_ = now;
        return;
    }
    if (current_ < 0) return;
    FrameSlot& slot = slots_[current_];
    if (slot.marks >= kMaxPasses) return;
    slot.passes[slot.marks] = pass;
    ++slot.marks;
    gl_->QueryCounter(slot.queries[slot.marks].name(), GL_TIMESTAMP);
}

void GpuTimer::end_frame() {
    if (sync_) {
        latest_count_ = sync_count_;
        latest_frame_ = frames_begun_;
        for (int i = 0; i < sync_count_; ++i) {
            latest_passes_[i] = sync_passes_[i];
            latest_ms_[i] = sync_ms_[i];
        }
        return;
    }
    if (current_ >= 0) slots_[current_].pending = slots_[current_].marks > 0;
    current_ = -1;
}

namespace {

// The host's GL_QUERY_BUFFER binding, set aside for the scope: while a buffer is bound there, glGetQueryObject*
// writes into it at the offset its pointer names (an invalid operation for a stack address) instead of reading back.
class QueryBufferSetAside {
public:
    QueryBufferSetAside(const gl::Table& gl, bool query_buffers) : gl_(gl) {
        if (query_buffers) gl.GetIntegerv(gl::kGlQueryBufferBinding, &host_binding_);
        if (host_binding_ != 0) gl.BindBuffer(gl::kGlQueryBuffer, 0);
    }
    ~QueryBufferSetAside() {
        if (host_binding_ != 0) gl_.BindBuffer(gl::kGlQueryBuffer, GLuint(host_binding_));
    }
    QueryBufferSetAside(const QueryBufferSetAside&) = delete;
    QueryBufferSetAside& operator=(const QueryBufferSetAside&) = delete;

private:
    const gl::Table& gl_;
    GLint host_binding_ = 0;
};

}  // namespace

void GpuTimer::collect() {
    bool pending = false;
    for (const FrameSlot& slot : slots_) pending = pending || slot.pending;
    if (!pending) return;
    QueryBufferSetAside set_aside(*gl_, query_buffers_);
    // Oldest first, so the newest complete frame ends up in latest_*.
    for (int i = 0; i < kFramesInFlight; ++i) {
        FrameSlot& slot = slots_[(next_ + i) % kFramesInFlight];
        if (!slot.pending) continue;
        GLuint available = 0;
        gl_->GetQueryObjectuiv(slot.queries[slot.marks].name(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) continue;
        GLuint64 previous = 0;
        gl_->GetQueryObjectui64v(slot.queries[0].name(), GL_QUERY_RESULT, &previous);
        for (int m = 0; m < slot.marks; ++m) {
            GLuint64 stamp = 0;
            gl_->GetQueryObjectui64v(slot.queries[m + 1].name(), GL_QUERY_RESULT, &stamp);
            latest_passes_[m] = slot.passes[m];
            latest_ms_[m] = stamp >= previous ? double(stamp - previous) * 1e-6 : 0.0;
            previous = stamp;
        }
        latest_count_ = slot.marks;
        latest_frame_ = slot.frame_index;
        slot.pending = false;
    }
}

uint32_t GpuTimer::latest(obscura_timing* out, uint32_t capacity, uint64_t* frame_index) {
    if (!sync_ && gl_) collect();
    *frame_index = latest_count_ > 0 ? latest_frame_ : 0;
    if (latest_count_ == 0) return 0;
    PassId passes[kMaxPasses] = {};
    double ms[kMaxPasses] = {};
    int count = 0;
    double total = 0.0;
    for (int i = 0; i < latest_count_; ++i) {
        total += latest_ms_[i];
        int j = 0;
        while (j < count && passes[j] != latest_passes_[i]) ++j;
        if (j == count) passes[count++] = latest_passes_[i];
        ms[j] += latest_ms_[i];
    }
    const uint32_t available = uint32_t(count) + 1;
    if (out && capacity > 0) out[0] = {"total", total};
    for (uint32_t i = 1; out && i < capacity && i < available; ++i) out[i] = {pass_label(passes[i - 1]), ms[i - 1]};
    return available;
}

}  // namespace obscura
