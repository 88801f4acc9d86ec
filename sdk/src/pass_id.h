// Every pass a frame can time, declared once: the timer records these ids, obscura_get_timings reports their
// labels, and each method's registry row lists the ones its frames can report (docs and tests read that list).
#ifndef OBSCURA_PASS_ID_H
#define OBSCURA_PASS_ID_H

#include <cstddef>
#include <cstdint>

namespace obscura {

// X(id, label): the label is the public timing label (obscura_timing.label), never changed once released.
#define OBSCURA_PASS_LIST(X)                 \
    X(DepthPrepare, "depth_prepare")         \
    X(Hbao, "hbao")                          \
    X(Reference, "reference")                \
    X(ZPyramid, "z_pyramid")                 \
    X(Sao, "sao")                            \
    X(LineSweep, "line_sweep")               \
    X(Gather, "gather")                      \
    X(FfaoTable, "ffao_table")               \
    X(FfaoScan, "ffao_scan")                 \
    X(FfaoPrefix, "ffao_prefix")             \
    X(FfaoBoxAverage, "ffao_box_average")    \
    X(FfaoObscurance, "ffao_obscurance")     \
    X(FfaoGather, "ffao_gather")             \
    X(Gtao, "gtao")                          \
    X(GtaoDenoise, "gtao_denoise")           \
    X(Blur, "blur")                          \
    X(Temporal, "temporal")                  \
    X(Upsample, "upsample")                  \
    X(Composite, "composite")

#define OBSCURA_PASS_ENUM_ENTRY_(id, label) id,
enum class PassId : uint8_t { OBSCURA_PASS_LIST(OBSCURA_PASS_ENUM_ENTRY_) Count };
#undef OBSCURA_PASS_ENUM_ENTRY_

// The public label of a pass ("hbao"); a static string.
inline const char* pass_label(PassId pass) {
#define OBSCURA_PASS_LABEL_ENTRY_(id, label) label,
    static const char* const kLabels[] = {OBSCURA_PASS_LIST(OBSCURA_PASS_LABEL_ENTRY_)};
#undef OBSCURA_PASS_LABEL_ENTRY_
    static_assert(sizeof kLabels / sizeof kLabels[0] == size_t(PassId::Count), "one label per pass");
    return size_t(pass) < size_t(PassId::Count) ? kLabels[size_t(pass)] : "?";
}

}  // namespace obscura

#endif  // OBSCURA_PASS_ID_H
