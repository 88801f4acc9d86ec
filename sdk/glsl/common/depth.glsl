// The one place that knows the depth conventions: window depth -> linear view depth (for every
// projection the SDK accepts), and linear view depth + pixel -> view-space position.
// Needs FrameConstants (shader_interface.h).

bool obscura_is_sky(float view_depth) { return !(view_depth < OBSCURA_SKY_THRESHOLD); }

// Finite test on the bits: drivers may compile float comparisons as if NaN did not exist (NVIDIA folds
// isnan() and !(x > 0.0) into x <= 0.0), so only the exponent field reliably tells NaN and inf apart.
bool obscura_is_finite(float x) { return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u; }

// Zero or denormal, on the bits: CPU rasterisers and GPUs flush denormals in some operations and not in others
// (llvmpipe compared a denormal depth > 0 and then divided by zero), so depths that small count as zero.
bool obscura_is_zero_or_denormal(float x) { return (floatBitsToUint(x) & 0x7f800000u) == 0u; }

// Window depth written through the host projection -> positive view distance, or OBSCURA_SKY_DEPTH.
float obscura_linearize_window_depth(float window_depth) {
    if (!obscura_is_finite(window_depth) || window_depth == depth_params.x) return OBSCURA_SKY_DEPTH;
    float z_ndc = window_depth * proj_offset.z + proj_offset.w;
    // Solve z_ndc = (m10 z + m14) / (m11 z + m15): covers perspective and orthographic, standard and
    // reversed-Z, finite and infinite far planes.
    float z = (proj_depth.y - z_ndc * proj_depth.w) / (z_ndc * proj_depth.z - proj_depth.x);
    float distance = -z;
    if (!obscura_is_finite(distance) || obscura_is_zero_or_denormal(distance) || !(distance > 0.0) ||
        !(distance < OBSCURA_SKY_THRESHOLD)) {
        return OBSCURA_SKY_DEPTH;
    }
    return distance;
}

// Linear depth given by the host: anything non-positive or non-finite is sky.
float obscura_sanitize_linear_depth(float view_depth) {
    if (!obscura_is_finite(view_depth) || obscura_is_zero_or_denormal(view_depth) || !(view_depth > 0.0) ||
        !(view_depth < OBSCURA_SKY_THRESHOLD)) {
        return OBSCURA_SKY_DEPTH;
    }
    return view_depth;
}

bool obscura_is_perspective() { return proj_depth.z != 0.0; }

// Clip w of a view point at distance `view_depth`: the distance itself (perspective) or 1 (orthographic).
float obscura_clip_w(float view_depth) { return -view_depth * proj_depth.z + proj_depth.w; }

// View-space position (camera looks down -z) of the point at `pixel_position` (texel units, texel centres at
// .5) and distance `view_depth`.
vec3 obscura_view_position_at(vec2 pixel_position, float view_depth) {
    vec2 ndc = pixel_position * depth_params.zw * 2.0 - 1.0;
    float z = -view_depth;
    float w = obscura_clip_w(view_depth);
    // ndc.x = (m0 x + m8 z + m12) / w, likewise y. Times the reciprocal rather than divided: most methods' taps come
    // here (HBAO's and GTAO's through axis forms, below), and CPU rasterisers divide at a fraction of their multiply
    // rate (2-6 % of HBAO's, GTAO's and SAO's frames on llvmpipe).
    vec2 xy = (ndc * w - proj_scale.zw * z - proj_offset.xy) * (1.0 / proj_scale.xy);
    return vec3(xy, z);
}

// The same for four points at once (lanes of the vec4s: pixel positions x, y and distances): out x, y; z is -view_depth.
void obscura_view_position_at4(vec4 pixel_x, vec4 pixel_y, vec4 view_depth, out vec4 x, out vec4 y) {
    vec4 ndc_x = pixel_x * depth_params.z * 2.0 - 1.0, ndc_y = pixel_y * depth_params.w * 2.0 - 1.0;
    vec4 z = -view_depth;
    vec4 w = -view_depth * proj_depth.z + proj_depth.w;
    x = (ndc_x * w - proj_scale.z * z - proj_offset.x) * (1.0 / proj_scale.x);
    y = (ndc_y * w - proj_scale.w * z - proj_offset.y) * (1.0 / proj_scale.y);
}

// A view-space axis as an affine form of a point's pixel position o and distance d: the point's coordinate along
// `axis` relative to `origin`, dot(obscura_view_position_at(o, d) - origin, axis), is
// obscura_clip_w(d) dot(o, f.xy) + d f.z + f.w (the projection is affine in o times clip w, and in d). Passes that
// project many taps onto a few axes (HBAO's and GTAO's slices) build the forms once per axis: a tap then costs
// two multiply-adds per axis and its clip w, where its view position and a 3D dot product per axis took about
// twice the arithmetic.
vec4 obscura_axis_form(vec3 axis, vec3 origin) {
    vec2 inverse_scale = 1.0 / proj_scale.xy;
    vec2 per_pixel = 2.0 * depth_params.zw * inverse_scale;                 // xy = clip_w o per_pixel + ...
    vec2 per_depth = (proj_depth.z + proj_scale.zw) * inverse_scale;        // ... + d per_depth + ...
    vec2 constant = -(proj_depth.w + proj_offset.xy) * inverse_scale;       // ... + constant; z = -d
    return vec4(per_pixel * axis.xy, dot(per_depth, axis.xy) - axis.z, dot(constant, axis.xy) - dot(origin, axis));
}

// The coordinate of the point at pixel position o and distance d (clip w: obscura_clip_w(d)) along an axis form.
float obscura_along_axis(vec4 form, vec2 pixel_position, float view_depth, float clip_w) {
    return clip_w * dot(pixel_position, form.xy) + (view_depth * form.z + form.w);
}

// View-space position of the centre of texel `pixel` at distance `view_depth`.
vec3 obscura_view_position(ivec2 pixel, float view_depth) {
    return obscura_view_position_at(vec2(pixel) + 0.5, view_depth);
}

// Pixels covered by one view unit at distance `view_depth`, along y (square pixels assumed for x).
// abs(): a y-flipped projection (render-to-texture conventions) has m5 < 0.
float obscura_pixels_per_view_unit(float view_depth) {
    return 0.5 * abs(proj_scale.y) * float(depth_size.y) / obscura_clip_w(view_depth);
}

// The distance that tolerances relative to "the pixel's distance" scale with (the denoisers' and the upsample's plane
// tests, the temporal pass's, LSAO's gather, the normal reconstruction's planarity), for the perspective distance
// `perspective_distance` (the view depth or |position|, as the caller measures it). A perspective pixel's footprint
// grows with its distance; an orthographic one is the same at every depth, and where the eye plane sits changes
// nothing in the image (an orthographic camera slid along its axis shifts every depth by a constant): there the
// distance from which a 60-degree perspective view has the same footprint, half the view's height / tan 30 degrees
// = sqrt(3) / |m5|. (Depth-relative tolerances once made an orthographic camera 1000 units back blur AO across
// every edge.)
float obscura_orthographic_distance() { return 1.7320508 / abs(proj_scale.y); }
float obscura_tolerance_distance(float perspective_distance) {
    return obscura_is_perspective() ? perspective_distance : obscura_orthographic_distance();
}

// Unit vector from a view-space point towards the eye: the eye itself (perspective) or +z (orthographic).
vec3 obscura_towards_eye(vec3 position) {
    return obscura_is_perspective() ? normalize(-position) : vec3(0.0, 0.0, 1.0);
}

