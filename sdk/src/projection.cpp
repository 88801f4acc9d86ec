#include "projection.h"

#include <cmath>

namespace obscura {
namespace {

bool is_perspective_shape(const float* m) {
    // Column-major: w_clip = m3 x + m7 y + m11 z + m15. A GL perspective has w = -z.
    return m[3] == 0.0f && m[7] == 0.0f && m[11] < 0.0f && m[15] == 0.0f;
}

bool is_orthographic_shape(const float* m) {
    return m[3] == 0.0f && m[7] == 0.0f && m[11] == 0.0f && m[15] != 0.0f && m[10] != 0.0f;
}

bool has_projection_shape(const float* m) {
    // x and y must not mix (no rotation inside the projection), scales must be non-zero, and depth must not
    // depend on x or y.
    if (m[0] == 0.0f || m[5] == 0.0f) return false;
    if (m[1] != 0.0f || m[4] != 0.0f || m[2] != 0.0f || m[6] != 0.0f) return false;
    return is_perspective_shape(m) || is_orthographic_shape(m);
}

void transpose(const float* in, float* out) {
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) out[col * 4 + row] = in[row * 4 + col];
}

}  // namespace

double view_z_from_window_depth(const ProjectionInfo& info, double window_depth) {
    const float* m = info.m;
    double z_ndc = window_depth * info.clip_scale + info.clip_bias;
    // Solve z_ndc = (m10 z + m14) / (m11 z + m15) for z; valid for both projection kinds.
    double denominator = z_ndc * m[11] - m[10];
    return (m[14] - z_ndc * m[15]) / denominator;
}

Error decode_projection(const float matrix[16], obscura_matrix_layout layout, obscura_clip_depth clip_depth,
                        obscura_depth_kind depth_kind, ProjectionInfo* out) {
    if (layout != OBSCURA_MATRIX_COLUMN_MAJOR && layout != OBSCURA_MATRIX_ROW_MAJOR) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "projection_layout = %d is not an obscura_matrix_layout",
                           int(layout));
    }
    if (clip_depth != OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE && clip_depth != OBSCURA_CLIP_DEPTH_ZERO_TO_ONE) {
        return Error::make(OBSCURA_STATUS_INVALID_ENUM, "clip_depth = %d is not an obscura_clip_depth", int(clip_depth));
    }
    for (int i = 0; i < 16; ++i) {
        if (!std::isfinite(matrix[i])) {
            return Error::make(OBSCURA_STATUS_INVALID_PROJECTION, "projection[%d] is not finite", i);
        }
    }
    ProjectionInfo info;
    if (layout == OBSCURA_MATRIX_ROW_MAJOR) transpose(matrix, info.m);
    else for (int i = 0; i < 16; ++i) info.m[i] = matrix[i];

    if (!has_projection_shape(info.m)) {
        float transposed[16];
        transpose(info.m, transposed);
        if (has_projection_shape(transposed)) {
            return Error::make(OBSCURA_STATUS_PROJECTION_TRANSPOSED,
                               "the projection matrix looks transposed: its perspective/translation terms are in the "
                               "bottom row; pass it column-major or set projection_layout = OBSCURA_MATRIX_ROW_MAJOR");
        }
        return Error::make(OBSCURA_STATUS_INVALID_PROJECTION,
                           "the projection matrix is neither a GL perspective (m[11] < 0, m[15] = 0) nor an "
                           "orthographic (m[11] = 0, m[15] != 0) matrix, or it rotates x/y");
    }
    // A transposed standard perspective (m14 < 0) keeps the perspective shape: m11 and m14 swap and both
    // stay negative. GL perspective matrices have w = -z exactly (m11 = -1), so one whose m14 is -1 while
    // m11 is not is taken for that matrix transposed.
    if (is_perspective_shape(info.m) && info.m[14] == -1.0f && info.m[11] != -1.0f) {
        return Error::make(OBSCURA_STATUS_PROJECTION_TRANSPOSED,
                           "the projection matrix looks transposed: m[14] is -1 (the w = -z term) and m[11] is %g; "
                           "pass it column-major or set projection_layout = OBSCURA_MATRIX_ROW_MAJOR",
                           double(info.m[11]));
    }
    // Normalise the homogeneous scale so w = -z (perspective) or w = 1 (orthographic).
    info.perspective = is_perspective_shape(info.m);
    float scale = info.perspective ? -info.m[11] : info.m[15];
    for (float& v : info.m) v /= scale;
    // Checked after the normalisation, which can overflow (a tiny w scale) or leave denormal x/y scales whose
    // reciprocals, which every pass takes, are infinite: the frame then rendered unoccluded with status OK.
    for (int i = 0; i < 16; ++i) {
        if (!std::isfinite(info.m[i])) {
            return Error::make(OBSCURA_STATUS_INVALID_PROJECTION,
                               "projection[%d] divided by the w scale %g is not finite", i, double(scale));
        }
    }
    if (!std::isnormal(info.m[0]) || !std::isnormal(info.m[5])) {
        return Error::make(OBSCURA_STATUS_INVALID_PROJECTION,
                           "the projection's x and y scales (%g, %g once w is normalised) must be normal floats",
                           double(info.m[0]), double(info.m[5]));
    }

    info.clip_scale = clip_depth == OBSCURA_CLIP_DEPTH_ZERO_TO_ONE ? 1.0f : 2.0f;
    info.clip_bias = clip_depth == OBSCURA_CLIP_DEPTH_ZERO_TO_ONE ? 0.0f : -1.0f;

    // Depth direction: compare the window depth of two view depths in front of the camera.
    auto window_depth = [&](double z) {
        double z_ndc = (info.m[10] * z + info.m[14]) / (info.m[11] * z + info.m[15]);
        return (z_ndc - info.clip_bias) / info.clip_scale;
    };
    double near_z, far_z;
    if (info.perspective) {
        // Any two depths in front of the eye; for a perspective matrix the near plane is at m14/(m10 - 1) or similar,
        // so probe relative to the magnitude of the terms.
        double n = std::fabs(info.m[14]) > 0.0 ? std::fabs(info.m[14]) : 1.0;
        near_z = -n;
        far_z = -4.0 * n;
        if (info.m[10] == -1.0f || info.m[10] == 0.0f) info.infinite_far = true;
        // An infinite far plane in float: m10 within an ulp or two of -1 (standard) or 0 (reversed).
        if (std::fabs(info.m[10] + 1.0f) < 1e-6f || std::fabs(info.m[10]) < 1e-6f) info.infinite_far = true;
    } else {
        double center = -info.m[14] / info.m[10];
        double half = std::fabs(1.0 / info.m[10]);
        near_z = center + 0.5 * half;
        far_z = center - 0.5 * half;
    }
    double d_near = window_depth(near_z);
    double d_far = window_depth(far_z);
    if (!(std::isfinite(d_near) && std::isfinite(d_far)) || d_near == d_far) {
        return Error::make(OBSCURA_STATUS_INVALID_PROJECTION, "the projection maps every depth to one value");
    }
    info.reversed_z = d_far < d_near;
    info.sky_window_depth = info.reversed_z ? 0.0f : 1.0f;
    if (!info.perspective && depth_kind == OBSCURA_DEPTH_HARDWARE) {
        // When the near plane (window depth 0, or 1 when reversed) is at or behind the eye, move it to z = -1:
        // z' = z - shift, so every visible point has a positive distance. (Linear depth is the host's distance: its
        // points behind the eye are sky, as obscura.h says, and its view space stays the host's.)
        double z_near = view_z_from_window_depth(info, info.reversed_z ? 1.0 : 0.0);
        if (z_near > -1e-6) {
            float shift = float(z_near + 1.0);
            info.m[12] += info.m[8] * shift;
            info.m[13] += info.m[9] * shift;
            info.m[14] += info.m[10] * shift;
            info.view_z_shift = shift;
        }
    }
    *out = info;
    return Error();
}

}  // namespace obscura
