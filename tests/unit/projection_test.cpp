// Projection decoding (sdk/src/projection.h): every matrix kind GL can use, layouts, rejection of
// transposed, garbage and non-finite matrices, and the window-depth -> view-z inverse checked against
// closed-form depth mappings.
//
// Tolerances: the matrices hold float entries, so view_z_from_window_depth inverts a slightly
// perturbed mapping. For a standard [-1,1] perspective the solve divides by (z_ndc * m11 - m10), which
// near the far plane is 2n/(f-n) computed from m10 ~ -1 in float: relative error ~ ulp(1) * (f-n)/(2n)
// = 6e-8 * 500 = 3e-5 for n = 0.1, f = 100; we allow 1e-4. Reversed-Z, infinite and orthographic
// mappings are well conditioned: 1e-6 relative.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>

#include "projection.h"

namespace {

using obscura::decode_projection;
using obscura::ProjectionInfo;
using obscura::view_z_from_window_depth;

constexpr double kNear = 0.1;
constexpr double kFar = 100.0;
constexpr float kFovY = 1.0471975512f;  // 60 degrees
constexpr float kAspect = 16.0f / 9.0f;

struct Matrix {
    float m[16];
};

Matrix from_glm(const glm::mat4& matrix) {
    Matrix out;
    std::memcpy(out.m, glm::value_ptr(matrix), sizeof out.m);  // GLM is column-major like GL
    return out;
}

Matrix transposed(const Matrix& in) {
    Matrix out;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) out.m[col * 4 + row] = in.m[row * 4 + col];
    return out;
}

// Perspective with an explicit depth row: clip z = a * z + b, clip w = -z.
Matrix perspective_with_depth_row(float a, float b) {
    glm::mat4 p = glm::perspectiveRH_NO(kFovY, kAspect, float(kNear), float(kFar));
    p[2][2] = a;
    p[3][2] = b;
    return from_glm(p);
}

Matrix standard_perspective() { return from_glm(glm::perspectiveRH_NO(kFovY, kAspect, float(kNear), float(kFar))); }
// Reversed-Z with [0,1] clip depth: the ZO matrix with near and far swapped.
Matrix reversed_perspective_zo() { return from_glm(glm::perspectiveRH_ZO(kFovY, kAspect, float(kFar), float(kNear))); }
Matrix reversed_perspective_no() { return from_glm(glm::perspectiveRH_NO(kFovY, kAspect, float(kFar), float(kNear))); }
// Infinite far, [-1,1]: z_ndc = 1 + 2n/z.
Matrix infinite_perspective() { return perspective_with_depth_row(-1.0f, -2.0f * float(kNear)); }
// Infinite far, reversed, [0,1]: z_ndc = -n/z.
Matrix reversed_infinite_perspective() { return perspective_with_depth_row(0.0f, float(kNear)); }
Matrix orthographic() { return from_glm(glm::orthoRH_NO(-4.0f, 4.0f, -2.25f, 2.25f, float(kNear), float(kFar))); }

// Closed-form window depth of view z (negative in front of the camera).
double window_standard(double z) {
    double z_ndc = (kFar + kNear) / (kFar - kNear) + 2.0 * kFar * kNear / ((kFar - kNear) * z);
    return z_ndc * 0.5 + 0.5;
}
double window_reversed_zo(double z) { return -kNear / (kFar - kNear) - kNear * kFar / ((kFar - kNear) * z); }
double window_infinite(double z) { return (1.0 + 2.0 * kNear / z) * 0.5 + 0.5; }
double window_reversed_infinite(double z) { return -kNear / z; }
double window_ortho(double z) { return (-z - kNear) / (kFar - kNear); }

ProjectionInfo decode_ok(const Matrix& matrix, obscura_clip_depth clip,
                         obscura_matrix_layout layout = OBSCURA_MATRIX_COLUMN_MAJOR) {
    ProjectionInfo info;
    obscura::Error error = decode_projection(matrix.m, layout, clip, OBSCURA_DEPTH_HARDWARE, &info);
    EXPECT_TRUE(error.ok()) << error.message();
    return info;
}

obscura_status decode_status(const Matrix& matrix, obscura_clip_depth clip = OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE,
                             obscura_matrix_layout layout = OBSCURA_MATRIX_COLUMN_MAJOR) {
    ProjectionInfo info;
    return decode_projection(matrix.m, layout, clip, OBSCURA_DEPTH_HARDWARE, &info).status();
}

void expect_inverse(const ProjectionInfo& info, double (*window)(double), double relative_tolerance) {
    for (double z : {-kNear, -0.5, -1.0, -3.7, -10.0, -42.0, -kFar}) {
        double d = window(z);
        double recovered = view_z_from_window_depth(info, d);
        EXPECT_NEAR(recovered, z, std::fabs(z) * relative_tolerance) << "window depth " << d;
    }
}

// ---- Each projection kind --------------------------------------------------------------------------

TEST(ProjectionDecode, StandardPerspective) {
    ProjectionInfo info = decode_ok(standard_perspective(), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_TRUE(info.perspective);
    EXPECT_FALSE(info.reversed_z);
    EXPECT_FALSE(info.infinite_far);
    EXPECT_EQ(info.clip_scale, 2.0f);
    EXPECT_EQ(info.clip_bias, -1.0f);
    EXPECT_EQ(info.sky_window_depth, 1.0f);
    EXPECT_EQ(info.m[11], -1.0f);
    expect_inverse(info, window_standard, 1e-4);
}

TEST(ProjectionDecode, StandardPerspectiveNearAndFarPlanes) {
    ProjectionInfo info = decode_ok(standard_perspective(), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_NEAR(view_z_from_window_depth(info, 0.0), -kNear, kNear * 1e-5);
    EXPECT_NEAR(view_z_from_window_depth(info, 1.0), -kFar, kFar * 1e-4);
}

TEST(ProjectionDecode, ReversedZZeroToOne) {
    ProjectionInfo info = decode_ok(reversed_perspective_zo(), OBSCURA_CLIP_DEPTH_ZERO_TO_ONE);
    EXPECT_TRUE(info.perspective);
    EXPECT_TRUE(info.reversed_z);
    EXPECT_FALSE(info.infinite_far);
    EXPECT_EQ(info.clip_scale, 1.0f);
    EXPECT_EQ(info.clip_bias, 0.0f);
    EXPECT_EQ(info.sky_window_depth, 0.0f);
    expect_inverse(info, window_reversed_zo, 1e-6);
    EXPECT_NEAR(view_z_from_window_depth(info, 1.0), -kNear, kNear * 1e-6);
    EXPECT_NEAR(view_z_from_window_depth(info, 0.0), -kFar, kFar * 1e-6);
}

TEST(ProjectionDecode, ReversedZNegativeOneToOne) {
    // Reversed-Z without glClipControl: near -> window 1, far -> window 0 through [-1,1].
    ProjectionInfo info = decode_ok(reversed_perspective_no(), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_TRUE(info.reversed_z);
    EXPECT_EQ(info.sky_window_depth, 0.0f);
    EXPECT_NEAR(view_z_from_window_depth(info, 1.0), -kNear, kNear * 1e-4);
    EXPECT_NEAR(view_z_from_window_depth(info, 0.0), -kFar, kFar * 1e-4);
}

TEST(ProjectionDecode, InfiniteFarStandard) {
    ProjectionInfo info = decode_ok(infinite_perspective(), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_TRUE(info.perspective);
    EXPECT_FALSE(info.reversed_z);
    EXPECT_TRUE(info.infinite_far);
    EXPECT_EQ(info.sky_window_depth, 1.0f);
    expect_inverse(info, window_infinite, 1e-6);
}

TEST(ProjectionDecode, InfiniteFarReversed) {
    ProjectionInfo info = decode_ok(reversed_infinite_perspective(), OBSCURA_CLIP_DEPTH_ZERO_TO_ONE);
    EXPECT_TRUE(info.perspective);
    EXPECT_TRUE(info.reversed_z);
    EXPECT_TRUE(info.infinite_far);
    EXPECT_EQ(info.sky_window_depth, 0.0f);
    expect_inverse(info, window_reversed_infinite, 1e-6);
    // Very far points keep their precision with reversed infinite depth.
    EXPECT_NEAR(view_z_from_window_depth(info, window_reversed_infinite(-4000.0)), -4000.0, 4000.0 * 1e-6);
}

TEST(ProjectionDecode, Orthographic) {
    ProjectionInfo info = decode_ok(orthographic(), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_FALSE(info.perspective);
    EXPECT_FALSE(info.reversed_z);
    EXPECT_EQ(info.sky_window_depth, 1.0f);
    EXPECT_EQ(info.m[15], 1.0f);
    expect_inverse(info, window_ortho, 1e-6);
}

TEST(ProjectionDecode, OrthographicNearBehindEyeIsShiftedInFront) {
    // glOrtho(..., -8, 12): the near plane lies 8 units behind the eye, where "distance" would be negative.
    ProjectionInfo info = decode_ok(from_glm(glm::orthoRH_NO(-1.0f, 1.0f, -1.0f, 1.0f, -8.0f, 12.0f)),
                                    OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_FALSE(info.perspective);
    EXPECT_NEAR(info.view_z_shift, 9.0, 1e-5) << "near plane z = +8 moves to z = -1";
    EXPECT_NEAR(view_z_from_window_depth(info, 0.0), -1.0, 1e-5);   // near plane
    EXPECT_NEAR(view_z_from_window_depth(info, 1.0), -21.0, 1e-4);  // far plane: 20 units further
    EXPECT_NEAR(view_z_from_window_depth(info, 0.5), -11.0, 1e-4);  // linear in between
}

// Host linear depth is the host's distance from its eye plane: its view space is not moved (points behind the eye
// are sky), so that the temporal reprojection, which maps view spaces through the host's matrices, lands where the
// host's own would (until 2026-12-06 linear depth under such a projection reprojected a constant off: 0.013 of
// visibility under a turning camera against the same depth given as hardware depth, found by a read-only review).
TEST(ProjectionDecode, OrthographicNearBehindEyeIsNotShiftedForLinearDepth) {
    const Matrix matrix = from_glm(glm::orthoRH_NO(-1.0f, 1.0f, -1.0f, 1.0f, -8.0f, 12.0f));
    ProjectionInfo info;
    ASSERT_TRUE(decode_projection(matrix.m, OBSCURA_MATRIX_COLUMN_MAJOR, OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE,
                                  OBSCURA_DEPTH_LINEAR_VIEW, &info)
                    .ok());
    EXPECT_EQ(info.view_z_shift, 0.0f);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(info.m[i], matrix.m[i]) << i;
}

TEST(ProjectionDecode, OrthographicNearInFrontIsNotShifted) {
    ProjectionInfo info = decode_ok(orthographic(), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_EQ(info.view_z_shift, 0.0f);
}

TEST(ProjectionDecode, OrthographicReversed) {
    // Near and far swapped: window depth decreases with distance.
    ProjectionInfo info = decode_ok(from_glm(glm::orthoRH_ZO(-1.0f, 1.0f, -1.0f, 1.0f, float(kFar), float(kNear))),
                                    OBSCURA_CLIP_DEPTH_ZERO_TO_ONE);
    EXPECT_FALSE(info.perspective);
    EXPECT_TRUE(info.reversed_z);
    EXPECT_EQ(info.sky_window_depth, 0.0f);
    EXPECT_NEAR(view_z_from_window_depth(info, 1.0), -kNear, 1e-5);
    EXPECT_NEAR(view_z_from_window_depth(info, 0.0), -kFar, kFar * 1e-6);
}

TEST(ProjectionDecode, OffCentreFrustum) {
    const float l = -0.07f, r = 0.03f, b = -0.02f, t = 0.05f;
    Matrix matrix = from_glm(glm::frustumRH_NO(l, r, b, t, float(kNear), float(kFar)));
    ASSERT_NE(matrix.m[8], 0.0f);
    ASSERT_NE(matrix.m[9], 0.0f);
    ProjectionInfo info = decode_ok(matrix, OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_TRUE(info.perspective);
    EXPECT_FALSE(info.reversed_z);
    // The off-centre terms survive decoding (the shaders need them to place pixels).
    EXPECT_FLOAT_EQ(info.m[8], (r + l) / (r - l));
    EXPECT_FLOAT_EQ(info.m[9], (t + b) / (t - b));
    expect_inverse(info, window_standard, 1e-4);
}

TEST(ProjectionDecode, OffCentreOrthographic) {
    Matrix matrix = from_glm(glm::orthoRH_NO(-1.0f, 3.0f, 0.5f, 2.5f, float(kNear), float(kFar)));
    ASSERT_NE(matrix.m[12], 0.0f);
    ProjectionInfo info = decode_ok(matrix, OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_FALSE(info.perspective);
    EXPECT_FLOAT_EQ(info.m[12], -(3.0f + -1.0f) / (3.0f - -1.0f));
    expect_inverse(info, window_ortho, 1e-6);
}

TEST(ProjectionDecode, HomogeneousScaleIsNormalised) {
    Matrix scaled = standard_perspective();
    for (float& v : scaled.m) v *= 2.5f;
    ProjectionInfo a = decode_ok(standard_perspective(), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    ProjectionInfo b = decode_ok(scaled, OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
    EXPECT_EQ(b.m[11], -1.0f);
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(b.m[i], a.m[i], std::fabs(a.m[i]) * 1e-6f) << i;
}

// ---- Layouts ----------------------------------------------------------------------------------------

TEST(ProjectionLayout, RowMajorEqualsColumnMajor) {
    for (const Matrix& matrix : {standard_perspective(), reversed_perspective_zo(), orthographic(),
                                 from_glm(glm::frustumRH_NO(-0.07f, 0.03f, -0.02f, 0.05f, 0.1f, 100.0f))}) {
        ProjectionInfo column = decode_ok(matrix, OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE);
        ProjectionInfo row =
            decode_ok(transposed(matrix), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE, OBSCURA_MATRIX_ROW_MAJOR);
        EXPECT_EQ(std::memcmp(column.m, row.m, sizeof column.m), 0);
        EXPECT_EQ(column.perspective, row.perspective);
        EXPECT_EQ(column.reversed_z, row.reversed_z);
    }
}

TEST(ProjectionLayout, TransposedColumnMajorIsReported) {
    for (const Matrix& matrix : {standard_perspective(), reversed_perspective_zo(), infinite_perspective(),
                                 reversed_infinite_perspective(), orthographic()}) {
        EXPECT_EQ(decode_status(transposed(matrix)), OBSCURA_STATUS_PROJECTION_TRANSPOSED);
    }
}

TEST(ProjectionLayout, ColumnMajorFlaggedRowMajorIsReported) {
    EXPECT_EQ(decode_status(standard_perspective(), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE, OBSCURA_MATRIX_ROW_MAJOR),
              OBSCURA_STATUS_PROJECTION_TRANSPOSED);
}

// ---- Rejections ---------------------------------------------------------------------------------------

TEST(ProjectionReject, Garbage) {
    Matrix zeros{};
    EXPECT_EQ(decode_status(zeros), OBSCURA_STATUS_INVALID_PROJECTION);
    Matrix noise;
    for (int i = 0; i < 16; ++i) noise.m[i] = float((i * 7919) % 23) * 0.37f - 3.1f;
    EXPECT_EQ(decode_status(noise), OBSCURA_STATUS_INVALID_PROJECTION);
}

TEST(ProjectionReject, RotationInsideProjection) {
    glm::mat4 p = glm::perspectiveRH_NO(kFovY, kAspect, float(kNear), float(kFar)) *
                  glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(decode_status(from_glm(p)), OBSCURA_STATUS_INVALID_PROJECTION);
}

TEST(ProjectionReject, ViewMatrixMultipliedIn) {
    // A projection * view product (a common mistake) has depth depending on x and y.
    glm::mat4 p = glm::perspectiveRH_NO(kFovY, kAspect, float(kNear), float(kFar)) *
                  glm::lookAt(glm::vec3(1, 2, 3), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
    obscura_status status = decode_status(from_glm(p));
    EXPECT_EQ(status, OBSCURA_STATUS_INVALID_PROJECTION);
}

TEST(ProjectionReject, ZeroScale) {
    Matrix matrix = standard_perspective();
    matrix.m[0] = 0.0f;
    EXPECT_EQ(decode_status(matrix), OBSCURA_STATUS_INVALID_PROJECTION);
}

// Checked once normalised (2026-12-06, a read-only review): a denormal x scale passed (every pass takes 1 / m0, which
// is infinite, and the frame rendered unoccluded with status OK), and a tiny w scale overflowed m0 to infinity.
TEST(ProjectionReject, DenormalOrOverflowingScalesOnceNormalised) {
    Matrix denormal = standard_perspective();
    denormal.m[0] = 1e-40f;
    EXPECT_EQ(decode_status(denormal), OBSCURA_STATUS_INVALID_PROJECTION);
    Matrix tiny_w = standard_perspective();
    for (float& v : tiny_w.m) v *= 1e-20f;
    tiny_w.m[0] = 1e20f;  // finite as given, 1e40 once divided by w = 1e-20
    EXPECT_EQ(decode_status(tiny_w), OBSCURA_STATUS_INVALID_PROJECTION);
    Matrix scaled = standard_perspective();
    for (float& v : scaled.m) v *= 1e-20f;  // the same matrix at another homogeneous scale: fine
    EXPECT_EQ(decode_status(scaled), OBSCURA_STATUS_OK);
}

TEST(ProjectionReject, ConstantDepth) {
    // Every depth maps to one window depth: nothing can be linearised.
    EXPECT_EQ(decode_status(perspective_with_depth_row(0.0f, 0.0f)), OBSCURA_STATUS_INVALID_PROJECTION);
}

TEST(ProjectionReject, NaNAnywhere) {
    for (int i = 0; i < 16; ++i) {
        Matrix matrix = standard_perspective();
        matrix.m[i] = std::numeric_limits<float>::quiet_NaN();
        EXPECT_EQ(decode_status(matrix), OBSCURA_STATUS_INVALID_PROJECTION) << "NaN at " << i;
    }
}

TEST(ProjectionReject, InfinityAnywhere) {
    for (int i : {0, 5, 10, 11, 14, 15}) {
        Matrix matrix = standard_perspective();
        matrix.m[i] = -std::numeric_limits<float>::infinity();
        EXPECT_EQ(decode_status(matrix), OBSCURA_STATUS_INVALID_PROJECTION) << "inf at " << i;
    }
}

TEST(ProjectionReject, BadEnums) {
    EXPECT_EQ(decode_status(standard_perspective(), obscura_clip_depth(2)), OBSCURA_STATUS_INVALID_ENUM);
    EXPECT_EQ(decode_status(standard_perspective(), OBSCURA_CLIP_DEPTH_NEGATIVE_ONE_TO_ONE, obscura_matrix_layout(7)),
              OBSCURA_STATUS_INVALID_ENUM);
}

}  // namespace
