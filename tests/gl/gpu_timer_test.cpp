// The per-pass timer (sdk/src/gpu_timer.*) run directly: a pass marked several times in a frame (FFAO's chunks mark
// their scan, prefix sums and obscurance once per chunk) is reported once, with the sum of its intervals, where it
// was first marked; "total" is the sum of every interval.
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "gpu_timer.h"
#include "pass_test_support.h"

namespace {

class GpuTimerTest : public obscura_pass_test::PassTest {};

std::vector<obscura_timing> latest(obscura::GpuTimer& timer) {
    std::vector<obscura_timing> out(40);
    uint64_t frame = 0;
    out.resize(timer.latest(out.data(), uint32_t(out.size()), &frame));
    return out;
}

TEST_F(GpuTimerTest, RepeatedPassesAreReportedOnceWithTheirSum) {
    for (bool sync : {true, false}) {
        obscura::GpuTimer timer;
        timer.create(gl_, sync, /*query_buffers=*/true);
        const obscura::PassId marks[] = {obscura::PassId::DepthPrepare,   obscura::PassId::FfaoScan,
                                         obscura::PassId::FfaoObscurance, obscura::PassId::FfaoScan,
                                         obscura::PassId::FfaoObscurance, obscura::PassId::Composite};
        std::vector<obscura_timing> out;
        // Query results arrive frames later: render a few until one is complete.
        for (int frame = 0; frame < 8 && out.empty(); ++frame) {
            timer.begin_frame();
            for (obscura::PassId pass : marks) {
                std::this_thread::sleep_for(std::chrono::milliseconds(2));  // measurable intervals (sync timing)
                timer.mark(pass);
            }
            timer.end_frame();
            gl_.Finish();
            out = latest(timer);
        }
        ASSERT_EQ(out.size(), 5u) << "sync " << sync;
        const char* expected[] = {"total", "depth_prepare", "ffao_scan", "ffao_obscurance", "composite"};
        double sum = 0.0;
        for (size_t i = 0; i < out.size(); ++i) {
            EXPECT_EQ(std::string(out[i].label), expected[i]) << "sync " << sync;
            if (i > 0) sum += out[i].milliseconds;
        }
        EXPECT_NEAR(out[0].milliseconds, sum, 1e-9) << "sync " << sync;
        if (sync) {  // two 2 ms intervals each
            EXPECT_GE(out[2].milliseconds, 3.5);
            EXPECT_GE(out[3].milliseconds, 3.5);
        }
        timer.destroy();
    }
}

}  // namespace
