// Shared by the C++ passes and the GLSL shaders (included by both), so binding points, workgroup
// sizes and the uniform-block layout cannot drift apart. Only #defines and the std140 block that
// both languages can parse live here.
#ifndef OBSCURA_SHADER_INTERFACE_H
#define OBSCURA_SHADER_INTERFACE_H

// ---- Texture / image / buffer binding points -------------------------------------------------
// Texture units (samplers). The state guard saves and restores exactly these units.
#define OBSCURA_UNIT_DEPTH 0        // host depth (sampler2D or sampler2DMS)
#define OBSCURA_UNIT_NORMALS 1      // host normals, or the SDK's normal texture
#define OBSCURA_UNIT_LINEAR_DEPTH 2 // linear view depth (R32F)
#define OBSCURA_UNIT_SOURCE 3       // pass input (AO, blur intermediate)
#define OBSCURA_UNIT_LSAO_LINES 4   // LSAO's line records (usamplerBuffer, RGBA32UI; CPU rasterisers)
#define OBSCURA_UNIT_LSAO_VALUES 5  // LSAO's sweep values read by the gather (samplerBuffer, R16F; CPU rasterisers)
#define OBSCURA_UNIT_FFAO_TABLE 4   // FFAO's estimator table L (sampler3D, R32F, linear filtering)
#define OBSCURA_UNIT_FFAO_PEAKS 5   // FFAO's peaks read by the obscurance pass (samplerBuffer, RGBA32F; CPU rasterisers)
#define OBSCURA_UNIT_FFAO_COLUMNS 6 // FFAO's column records read by the obscurance pass (usamplerBuffer; CPU rasterisers)
#define OBSCURA_UNIT_MOTION 0       // the temporal pass: host motion vectors (the host depth is read only before)
#define OBSCURA_UNIT_HISTORY 4      // the temporal pass: the view's AO history (RG32F)
#define OBSCURA_UNIT_BENT_SOURCE 5  // the temporal pass: this frame's bent normals (RGBA16F)
#define OBSCURA_UNIT_BENT_HISTORY 6 // the temporal pass: the view's bent-normal history (RGBA32F)
#define OBSCURA_TEXTURE_UNIT_COUNT 7

// Image units (imageStore / imageLoad).
#define OBSCURA_IMAGE_OUT0 0
#define OBSCURA_IMAGE_OUT1 1
#define OBSCURA_IMAGE_OUT2 2
#define OBSCURA_IMAGE_OUT3 3
#define OBSCURA_IMAGE_OUT4 4
#define OBSCURA_IMAGE_OUT5 5
#define OBSCURA_IMAGE_UNIT_COUNT 6

// Uniform buffer binding points.
#define OBSCURA_UBO_FRAME 0
#define OBSCURA_UBO_PASS 1
#define OBSCURA_UBO_DISPATCH 2  // a pass that runs in several dispatches: what differs between them (FFAO's chunks)
#define OBSCURA_UBO_COUNT 3

// Shader storage buffer binding points.
#define OBSCURA_SSBO_LSAO_VALUES 0  // the sweeps' results, eight halves per uvec4
#define OBSCURA_SSBO_LSAO_STATS 1   // counters: steps, hull pops, points dropped from full hulls
#define OBSCURA_SSBO_LSAO_LINES 2   // LSAO's line records (GPUs read them as a storage buffer)
// FFAO reuses the same three bindings (a program belongs to one method).
#define OBSCURA_SSBO_FFAO_PEAKS 0   // per (line, interval): sums of (m0, m1 back, m1 forward, valid), prefix-summed
#define OBSCURA_SSBO_FFAO_COLUMNS 1 // per (orientation, level, interval): entry offset, first line, lines, block shift
#define OBSCURA_SSBO_FFAO_LINES 2   // per scan line: origin xy (float bits), first step, steps
#define OBSCURA_SSBO_COUNT 3
// FFAO's peaks come in chunks, runs of whole orientations. One chunk when all of them fit one storage block
// (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, 128 MiB on Mesa, and at most OBSCURA_FFAO_MAX_BLOCK_BYTES on any driver: GPUs
// allow gigabytes, and at 4K one block of 296 MiB took FFAO to 457 MiB); past that, chunks of OBSCURA_FFAO_CHUNK_BYTES
// (doubled up to the driver's block where 8 would not hold them):
// the scan, the prefix sums and the obscurance then run chunk by chunk through a buffer that holds one, and the
// obscurance carries its running sums from chunk to chunk in a texture (FfaoPass::ensure_layout).
#define OBSCURA_FFAO_PEAK_CHUNKS 8 // at most (the chunk size doubles from OBSCURA_FFAO_CHUNK_BYTES until they do)
#define OBSCURA_FFAO_CHUNK_BYTES (64 * 1024 * 1024)
#define OBSCURA_FFAO_MAX_BLOCK_BYTES (128 * 1024 * 1024)
// FfaoChunkConstants.range.w: the first chunk (no running sums to read), the last (the sums are complete).
#define OBSCURA_FFAO_CHUNK_FIRST 1
#define OBSCURA_FFAO_CHUNK_LAST 2

// ---- Workgroup sizes (the dispatch math in C++ reads the same numbers) ------------------------
#define OBSCURA_DEPTH_PREPARE_GROUP_X 8
#define OBSCURA_DEPTH_PREPARE_GROUP_Y 8
#define OBSCURA_DEPTH_PREPARE_CPU_BLOCK 4  // CPU rasterisers: texels per invocation on each axis (depth_prepare.comp)
#define OBSCURA_HBAO_GROUP_X 8
#define OBSCURA_HBAO_GROUP_Y 8
#define OBSCURA_BLUR_GROUP_X 8
#define OBSCURA_BLUR_GROUP_Y 8
#define OBSCURA_COMPOSITE_GROUP_X 8
#define OBSCURA_COMPOSITE_GROUP_Y 8
#define OBSCURA_REFERENCE_GROUP_X 8
#define OBSCURA_REFERENCE_GROUP_Y 8
// z pyramid: a group builds a 32x32 tile of the first level written and every level below it (16x16 threads on
// GPUs, 8x8 invocations on CPU rasterisers).
#define OBSCURA_Z_PYRAMID_GROUP 16
#define OBSCURA_Z_PYRAMID_GROUP_CPU 8  // CPU rasterisers: a 4x4 block of the tile's first level per invocation
#define OBSCURA_Z_PYRAMID_TILE 32
#define OBSCURA_Z_PYRAMID_LEVELS_PER_DISPATCH 6
// SAO: 8x8 groups (whole 2x2 quads for the quad filter; the work region starts on even coordinates).
#define OBSCURA_SAO_GROUP_X 8
#define OBSCURA_SAO_GROUP_Y 8
#define OBSCURA_SAO_MAX_SAMPLES 64
// GTAO: 8x8 groups for the slices and the denoise.
#define OBSCURA_GTAO_GROUP_X 8
#define OBSCURA_GTAO_GROUP_Y 8
#define OBSCURA_GTAO_DENOISE_GROUP_X 8
#define OBSCURA_GTAO_DENOISE_GROUP_Y 8
// Reduced resolution's upsample: 8x8 groups over the output rectangle (host texels).
#define OBSCURA_UPSAMPLE_GROUP_X 8
#define OBSCURA_UPSAMPLE_GROUP_Y 8
// Temporal accumulation: 8x8 groups over the output rectangle.
#define OBSCURA_TEMPORAL_GROUP_X 8
#define OBSCURA_TEMPORAL_GROUP_Y 8
// Pixels one GTAO denoise invocation filters along the pass's axis (the dispatch covers the region in runs of this,
// compiled in as OBSCURA_GTAO_DENOISE_RUN): long runs on CPU rasterisers, which pay per invocation and per read (16:
// the denoise at 0.8x of its time with 4 on llvmpipe; 32 gains nothing more), short ones on GPUs, which want the
// invocations (1920x1080 + 10 %: 750,000 with 4).
#define OBSCURA_GTAO_DENOISE_RUN_GPU 4
#define OBSCURA_GTAO_DENOISE_RUN_CPU 16
// Pixels one bilateral blur invocation filters along the pass's axis (compiled in as OBSCURA_BLUR_RUN), likewise: 16 on
// CPU rasterisers, one on GPUs (where the pass was measured that way).
#define OBSCURA_BLUR_RUN_GPU 1
#define OBSCURA_BLUR_RUN_CPU 16
// Pixels one SAO blur invocation filters (compiled in as OBSCURA_SAO_BLUR_RUN), likewise.
#define OBSCURA_SAO_BLUR_RUN_GPU 1
#define OBSCURA_SAO_BLUR_RUN_CPU 16
// LSAO: one invocation per line segment, 64 per group, each keeping its hull in shared memory (64 x hull
// capacity x 8 bytes: 12 KiB at the default 24 points, 32 KiB, GL's guaranteed minimum, at the most);
// the gather in 8x8 groups on CPU rasterisers and 16x16 on GPUs, whose groups share a tile of depths.
#define OBSCURA_LSAO_SWEEP_GROUP 64
#define OBSCURA_LSAO_GATHER_GROUP_X 8
#define OBSCURA_LSAO_GATHER_GROUP_Y 8
#define OBSCURA_LSAO_GPU_GATHER_GROUP 16
#define OBSCURA_LSAO_MAX_DIRECTIONS 64
#define OBSCURA_LSAO_MAX_HULL 64
// Every line's values start on a multiple of this many (the sweep stores 8 halves, 16 bytes, at a time).
#define OBSCURA_LSAO_VALUE_ALIGNMENT 8
// The value a sweep writes where no earlier sample exists (outside every sin h, which is <= 1).
#define OBSCURA_LSAO_NO_OCCLUDER 4.0

// FFAO: one invocation per scan line (scan), per interval column (prefix sums) and per table column; the
// obscurance pass in 8x8 pixel groups. The estimator table L(a, b, c, d) is an A x B x (C * D) 3D texture.
#define OBSCURA_FFAO_SCAN_GROUP 64
#define OBSCURA_FFAO_PREFIX_GROUP 64
#define OBSCURA_FFAO_TABLE_GROUP 64
#define OBSCURA_FFAO_GROUP_X 8
#define OBSCURA_FFAO_GROUP_Y 8
#define OBSCURA_FFAO_MAX_ORIENTATIONS 32
#define OBSCURA_FFAO_MAX_LEVELS 16
#define OBSCURA_FFAO_TABLE_A 32
#define OBSCURA_FFAO_TABLE_B 32
#define OBSCURA_FFAO_TABLE_C 16
#define OBSCURA_FFAO_TABLE_D 16

// ---- Conventions ---------------------------------------------------------------------------------
// Linear view depth is a positive distance from the eye plane in view units; sky pixels (far-plane
// clear value, NaN, inf, behind the eye, 1e18 view units or farther) are stored as OBSCURA_SKY_DEPTH and never occlude.
// The threshold keeps every position's squared length finite in 32-bit floats (to 1.8e19): a host's "miss" distance of
// 1e20 (a ray tracer's tmax) was geometry whose lengths overflowed (inf, then NaN normals and FFAO's scale).
#define OBSCURA_SKY_DEPTH 1.0e30
#define OBSCURA_SKY_THRESHOLD 1.0e18

// Depth-source kinds (FrameConstants.depth_mode.x).
#define OBSCURA_DEPTH_SOURCE_HARDWARE 0
#define OBSCURA_DEPTH_SOURCE_HARDWARE_MS 1
#define OBSCURA_DEPTH_SOURCE_LINEAR 2
#define OBSCURA_DEPTH_SOURCE_LINEAR_MS 3

// Normal-source kinds (FrameConstants.depth_mode.y).
#define OBSCURA_NORMALS_RECONSTRUCT 0
#define OBSCURA_NORMALS_SIGNED 1   // float / snorm texture, used as is
#define OBSCURA_NORMALS_UNSIGNED 2 // unorm texture, decoded as n * 2 - 1

// Debug views the passes themselves act on (FrameConstants.target_params.w; values of obscura_debug_view).
// The names differ from the API's so that both headers fit in one translation unit (shader_interface_checks.cpp).
#define OBSCURA_DEBUG_VIEW_LINEAR_DEPTH 1
#define OBSCURA_DEBUG_VIEW_NORMALS 2
#define OBSCURA_DEBUG_VIEW_TAP_COUNT 4

// Blend modes of the composite (FrameConstants.target_params.z; values of obscura_blend_mode).
#define OBSCURA_BLEND_MODE_OVERWRITE 0
#define OBSCURA_BLEND_MODE_MULTIPLY 1

// pi for both languages from one literal: GLSL reads it as a float, C++ as a double (math_constants.h).
#define OBSCURA_PI 3.14159265358979323846

// ---- Uniform block: per-frame constants every pass sees (std140, vec4/ivec4 members only) -------
#ifdef __cplusplus
#include <cstdint>
#define OBSCURA_VEC4(name) float name[4]
#define OBSCURA_IVEC4(name) int32_t name[4]
#define OBSCURA_BLOCK_BEGIN(name) struct name {
#define OBSCURA_BLOCK_END(name) };
#else
#define OBSCURA_VEC4(name) vec4 name
#define OBSCURA_IVEC4(name) ivec4 name
#define OBSCURA_BLOCK_BEGIN(name) layout(std140, binding = OBSCURA_UBO_FRAME) uniform name {
#define OBSCURA_BLOCK_END(name) };
#endif

OBSCURA_BLOCK_BEGIN(FrameConstants)
  // Projection terms (column-major m[i]) that map view space <-> clip space; see depth.glsl.
  OBSCURA_VEC4(proj_scale);     // m0, m5, m8, m9
  OBSCURA_VEC4(proj_depth);     // m10, m14, m11, m15
  OBSCURA_VEC4(proj_offset);    // m12, m13, clip-depth scale, clip-depth bias (z_ndc = d * s + b)
  OBSCURA_VEC4(depth_params);   // sky window depth, metres-to-view-units, 1/width, 1/height
  OBSCURA_IVEC4(depth_size);    // width, height, depth source kind, normal source kind (both informational: the
                                //   programs compile them in)
  OBSCURA_IVEC4(output_rect);   // x, y, width, height of the output rectangle in the depth texture
  OBSCURA_IVEC4(work_rect);     // x, y, width, height of the region a pass computes (rect + apron)
  OBSCURA_IVEC4(target_params); // target x, target y, blend mode, debug view
  OBSCURA_VEC4(debug_params);   // linear-depth debug scale (1 / (4 * radius in view units)), unused x3
  OBSCURA_VEC4(noise_offset);   // the frame index's offsets of the per-pixel noise in [0, 1) (R2 sequence; frame 0: 0),
                                // unused x2
  OBSCURA_IVEC4(resolution);    // reduced resolution: k, the host's texel of working texel t being t << k (0: full);
                                // the composite's AO source is at the working size (1) or the host's (0); unused x2
OBSCURA_BLOCK_END(FrameConstants)

// ---- Uniform blocks of single passes (binding OBSCURA_UBO_PASS) --------------------------------
// A shader declares the block it uses by defining OBSCURA_<PASS>_PASS before including this file;
// GLSL then sees it with an instance name (hbao.falloff, blur.params).
#ifdef __cplusplus
#define OBSCURA_PASS_BLOCK_BEGIN(name) struct name {
#define OBSCURA_PASS_BLOCK_END(name, instance) };
#else
#define OBSCURA_PASS_BLOCK_BEGIN(name) layout(std140, binding = OBSCURA_UBO_PASS) uniform name {
#define OBSCURA_PASS_BLOCK_END(name, instance) } instance;
#endif

#if defined(__cplusplus) || defined(OBSCURA_HBAO_PASS)
OBSCURA_PASS_BLOCK_BEGIN(HbaoConstants)
  OBSCURA_VEC4(falloff);   // decay r (view units^2), C, radius (view units), max radius in pixels
  OBSCURA_VEC4(shaping);   // bias, intensity, power, unused
  OBSCURA_IVEC4(counts);   // K directions, N steps, unused (the estimator is compiled in), unused
OBSCURA_PASS_BLOCK_END(HbaoConstants, hbao)
#endif

#if defined(__cplusplus) || defined(OBSCURA_BLUR_PASS)
OBSCURA_PASS_BLOCK_BEGIN(BlurConstants)
  OBSCURA_VEC4(params);    // sharpness, 1 / (2 sigma^2) of the spatial Gaussian, unused, unused
  OBSCURA_IVEC4(config);   // unused (the radius is compiled in: OBSCURA_BLUR_RADIUS), axis x, axis y, unused
OBSCURA_PASS_BLOCK_END(BlurConstants, blur)
#endif

// Falloff kinds (common/falloff.glsl): the values of obscura_falloff.
#define OBSCURA_FALLOFF_KIND_RHO0 1
#define OBSCURA_FALLOFF_KIND_INVERSE_QUADRATIC 2
#define OBSCURA_FALLOFF_KIND_EXPONENTIAL 3
#define OBSCURA_FALLOFF_KIND_TABLE 4

#if defined(__cplusplus) || defined(OBSCURA_REFERENCE_PASS)
OBSCURA_PASS_BLOCK_BEGIN(ReferenceConstants)
  OBSCURA_VEC4(falloff);   // decay r (view units^2), C, radius (view units), longest ray (view units)
  OBSCURA_VEC4(params);    // thickness (view units, 0: infinite), 1 / total rays, unused, unused
  OBSCURA_IVEC4(config);   // falloff kind, total rays, unused, unused
  OBSCURA_VEC4(table[4]);  // the 16 falloff-table values, 4 per vec4
OBSCURA_PASS_BLOCK_END(ReferenceConstants, reference)
#endif

// MIP filters of the z pyramid (OBSCURA_Z_PYRAMID_FILTER, OBSCURA_SAO_MIP_FILTER): the values of
// obscura_sao_settings.mip_filter.
#define OBSCURA_MIP_FILTER_ROTATED_GRID 1
#define OBSCURA_MIP_FILTER_MEAN 2
#define OBSCURA_MIP_FILTER_HARMONIC_MEAN 3
#define OBSCURA_MIP_FILTER_MIN 4
#define OBSCURA_MIP_FILTER_MAX 5
// Internal (FFAO's mipmap method, GTAO's under an orthographic projection, where depth is affine on screen): the mean
// of the children that are not sky; sky only if all four are.
#define OBSCURA_MIP_FILTER_MEAN_OF_GEOMETRY 6
// Internal (GTAO's): the harmonic mean of the children that are not sky. 1/z is affine in screen space on a plane,
// so on planes it is the depth at the block's centre, where GTAO reconstructs the sample.
#define OBSCURA_MIP_FILTER_HARMONIC_MEAN_OF_GEOMETRY 7

#if defined(__cplusplus) || defined(OBSCURA_Z_PYRAMID_PASS)
OBSCURA_PASS_BLOCK_BEGIN(ZPyramidConstants)
  OBSCURA_IVEC4(config);   // source level, levels written (1..6, to image units OUT0..), unused x2 (the filter is
                           // compiled in: OBSCURA_Z_PYRAMID_FILTER)
OBSCURA_PASS_BLOCK_END(ZPyramidConstants, z_pyramid)
#endif

#if defined(__cplusplus) || defined(OBSCURA_SAO_PASS)
OBSCURA_PASS_BLOCK_BEGIN(SaoConstants)
  OBSCURA_VEC4(ball);      // r, r^2 (view units), 2 sigma r / s, epsilon r^2
  OBSCURA_VEC4(shaping);   // beta, k, max screen radius (px), quad-filter edge scale (sharpness / depth range)
  OBSCURA_VEC4(packing);   // 1 / blur depth range (view units^-1), the depth the key counts from, unused x2
  OBSCURA_IVEC4(config);   // s, log2 q', deepest MIP level (0: level 0 only), quad filter on
  OBSCURA_IVEC4(options);  // unused x4 (the MIP filter is compiled in: OBSCURA_SAO_MIP_FILTER)
  OBSCURA_VEC4(taps[OBSCURA_SAO_MAX_SAMPLES]); // unrotated tap i: cos, sin of 2 pi tau alpha_i; alpha_i; unused
OBSCURA_PASS_BLOCK_END(SaoConstants, sao)
#endif

#if defined(__cplusplus) || defined(OBSCURA_SAO_BLUR_PASS)
OBSCURA_PASS_BLOCK_BEGIN(SaoBlurConstants)
  OBSCURA_VEC4(params);    // edge scale (sharpness, on the packed key), 1 / (2 sigma^2), unused, unused
  OBSCURA_IVEC4(config);   // unused (the radius is compiled in: OBSCURA_SAO_BLUR_RADIUS), stride, axis x, axis y
OBSCURA_PASS_BLOCK_END(SaoBlurConstants, sao_blur)
#endif

#if defined(__cplusplus) || defined(OBSCURA_GTAO_PASS)
// GTAO's thickness modes (compiled in: GtaoPass::prepare): the values of obscura_gtao_settings.thickness_mode.
#define OBSCURA_GTAO_MODE_HORIZON 1
#define OBSCURA_GTAO_MODE_BITMASK 2
OBSCURA_PASS_BLOCK_BEGIN(GtaoConstants)
  OBSCURA_VEC4(falloff);   // radius (view units), weight = clamp(d * x + y): its slope and offset, max radius (px)
  OBSCURA_VEC4(thickness); // bitmask thickness (view units), horizon blend, step power, MIP offset (log2 px)
  OBSCURA_VEC4(shaping);   // intensity, power, albedo (0: no multi-bounce), unused
  OBSCURA_IVEC4(config);   // unused x2 (slices and steps are compiled in), sectors, deepest z-pyramid level (0: level 0)
  OBSCURA_VEC4(noise);     // the frame's turns of the slice rotations, step jitters and bitmask draws (mod 1), unused
  OBSCURA_VEC4(rotation);  // cos and sin of pi / S (from one slice to the next), 2^-mip_offset, unused
OBSCURA_PASS_BLOCK_END(GtaoConstants, gtao)
#endif

#if defined(__cplusplus) || defined(OBSCURA_GTAO_DENOISE_PASS)
OBSCURA_PASS_BLOCK_BEGIN(GtaoDenoiseConstants)
  OBSCURA_VEC4(params);    // sharpness (per relative distance to the pixel's plane), unused x3
  OBSCURA_IVEC4(config);   // axis x, axis y, unused x2
OBSCURA_PASS_BLOCK_END(GtaoDenoiseConstants, gtao_denoise)
#endif

#if defined(__cplusplus) || defined(OBSCURA_TEMPORAL_PASS)
// Where the previous frame's position of a pixel comes from (compiled in: OBSCURA_TEMPORAL_REPROJECT, one program
// each, since CPU rasterisers run every lane through both sides of a branch).
#define OBSCURA_TEMPORAL_REPROJECT_MATRICES 0 // the two view-projections (through the depth)
#define OBSCURA_TEMPORAL_REPROJECT_MOTION 1   // the host's motion vectors
#define OBSCURA_TEMPORAL_REPROJECT_IDENTITY 2 // a static camera: the same texel
OBSCURA_PASS_BLOCK_BEGIN(TemporalConstants)
  OBSCURA_VEC4(reprojection[4]);  // columns: this frame's view space -> the previous frame's (homogeneous)
  OBSCURA_VEC4(params);    // max frames, clamp (deviations), plane tolerance, unused
  OBSCURA_VEC4(motion);    // motion vector -> texels: scale x, scale y (1 for pixels, size / 2 for NDC), unused x2
  OBSCURA_IVEC4(config);   // history valid (0: start anew), unused x3
OBSCURA_PASS_BLOCK_END(TemporalConstants, temporal)
#endif

#if defined(__cplusplus) || defined(OBSCURA_UPSAMPLE_PASS)
OBSCURA_PASS_BLOCK_BEGIN(UpsampleConstants)
  OBSCURA_VEC4(params);    // 1 / upsample tolerance, 1 / 2^k (host texels -> reduced texels), 1 / reduced width, height
  OBSCURA_IVEC4(config);   // the reduced grid's last texel x, y; k; unused
OBSCURA_PASS_BLOCK_END(UpsampleConstants, upsample)
#endif

#if defined(__cplusplus) || defined(OBSCURA_BENT_NORMAL_WRITE_PASS)
OBSCURA_PASS_BLOCK_BEGIN(BentNormalWriteConstants)
  OBSCURA_IVEC4(config);   // x, y of the output rectangle in the host's bent-normal texture, unused x2
OBSCURA_PASS_BLOCK_END(BentNormalWriteConstants, bent_normal_write)
#endif

#if defined(__cplusplus) || defined(OBSCURA_LSAO_PASS)
// LsaoConstants.config.w flags.
// (The pattern, tangent strategy, hull capacity and normal test are compiled in: see LsaoPass::prepare.)
#define OBSCURA_LSAO_FLAG_STATS 8  // the sweep counts steps, pops and drops (tests)
OBSCURA_PASS_BLOCK_BEGIN(LsaoConstants)
  OBSCURA_VEC4(falloff);   // r (view units^2), C (0: r / (r + d^2)), fixed sin t, D_L (texels)
  OBSCURA_VEC4(gather);    // depth threshold (relative), normal threshold (dot), intensity, power
  OBSCURA_IVEC4(config);   // K, unused (the sweep bounds lines per direction by coverage.w), unused, flags
  OBSCURA_IVEC4(sweep);    // warm-up stride, segment steps (0: whole lines), unused x2
  OBSCURA_VEC4(warmup);    // segments' warm-up distance (view units; < 0: from the line start), unused x3
  OBSCURA_VEC4(directions[OBSCURA_LSAO_MAX_DIRECTIONS]); // unit direction xy, step vector xy (texels)
  OBSCURA_VEC4(coverage[OBSCURA_LSAO_MAX_DIRECTIONS]);   // weight, perpendicular offset of line 0, first line, line count
  OBSCURA_VEC4(axes[OBSCURA_LSAO_MAX_DIRECTIONS]);       // view-space screen axis of the direction, 1 / |step|^2
OBSCURA_PASS_BLOCK_END(LsaoConstants, lsao)
#endif

#if defined(__cplusplus) || defined(OBSCURA_FFAO_TABLE_PASS)
// The table is built for the falloff's shape in units of its scale s (see FfaoConstants.shape.x).
OBSCURA_PASS_BLOCK_BEGIN(FfaoTableConstants)
  OBSCURA_VEC4(falloff);   // r, C, radius of the falloff in units of its scale, unused
  OBSCURA_IVEC4(config);   // falloff kind, unused x3
  OBSCURA_VEC4(table[4]);  // the 16 falloff-table values, 4 per vec4
OBSCURA_PASS_BLOCK_END(FfaoTableConstants, ffao_table)
#endif

#if defined(__cplusplus) || defined(OBSCURA_FFAO_CHUNK_PASS)
#ifdef __cplusplus
struct FfaoChunkConstants {
#else
layout(std140, binding = OBSCURA_UBO_DISPATCH) uniform FfaoChunkConstants {
#endif
  OBSCURA_IVEC4(range);    // the chunk's first orientation, its orientation count, the entry its buffer starts at
                           // (column offsets are global), OBSCURA_FFAO_CHUNK_* flags
#ifdef __cplusplus
};
#else
} ffao_chunk;
#endif
#endif

#if defined(__cplusplus) || defined(OBSCURA_FFAO_PASS)
OBSCURA_PASS_BLOCK_BEGIN(FfaoConstants)
  OBSCURA_VEC4(shape);     // falloff scale s (view units: the table's b axis is b / s), intensity, power,
                           // thickness (view units; 0: infinite)
  OBSCURA_VEC4(view);      // view units per texel at depth 1 along x and y (2 / (m0 W), 2 / (m5 H)), unused x2
  OBSCURA_IVEC4(config);   // K sectors, segments per sector, B0, pyramid levels
  OBSCURA_IVEC4(options);  // jitter, frame split N (1: every orientation), deepest depth MIP level (mipmap method),
                           // the frame's turn of the split's pattern (frame_index mod N). (Single lines, a finite
                           // thickness, are compiled in: OBSCURA_FFAO_FINITE_THICKNESS.)
  OBSCURA_VEC4(orientation[OBSCURA_FFAO_MAX_ORIENTATIONS]); // scan direction xy (texels), u and v of the grid origin
  OBSCURA_IVEC4(lines[OBSCURA_FFAO_MAX_ORIENTATIONS]);      // first line record, line count, grid steps U, unused
  OBSCURA_VEC4(axes[OBSCURA_FFAO_MAX_ORIENTATIONS]);        // view-space unit vector of the direction (z = 0): x, y
  // First column record of (orientation k, level n) at index k * OBSCURA_FFAO_MAX_LEVELS + n, 4 per ivec4;
  // column counts likewise.
  OBSCURA_IVEC4(column_base[OBSCURA_FFAO_MAX_ORIENTATIONS * OBSCURA_FFAO_MAX_LEVELS / 4]);
  OBSCURA_IVEC4(column_count[OBSCURA_FFAO_MAX_ORIENTATIONS * OBSCURA_FFAO_MAX_LEVELS / 4]);
OBSCURA_PASS_BLOCK_END(FfaoConstants, ffao)
#endif

#endif  // OBSCURA_SHADER_INTERFACE_H
