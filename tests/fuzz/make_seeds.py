#!/usr/bin/env python3
"""Writes the hand-made seed inputs of the fuzz targets into tests/fuzz/corpus/<target>/.

Each seed is a short byte string in the layout the target's LLVMFuzzerTestOneInput decodes (documented at the
top of settings_fuzzer.cpp and in render_fuzzer.cpp's decode_* functions); missing bytes read as zero, so a seed
only spells out what differs from zero. Run it again after changing a decoder:

    python3 tests/fuzz/make_seeds.py

The seeds give the fuzzer a successful call of every kind to mutate from: default settings of every method at
every released struct size, renders of every method from every depth format into every target kind (with
settings of every released size), prepare, the queries, a host GL error, another GL context current (with valid
and with invalid fields) and NULL arguments; and the 0.5 per-frame fields: GTAO with bent normals, temporal
sequences (matrices, motion vectors, views, camera cuts), reduced resolution, views created and destroyed, and
the refusals of each.

The script deletes every other file in corpus/<target>/: inputs that once failed live in regressions/<target>/,
which it never touches.
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# ---- settings_fuzzer -------------------------------------------------------------------------------------------
# flags (bit 0: struct_size the released size of bits 3-4, bit 1: small method (method % 8 - 1) into the struct,
# bit 2: XOR onto that method's defaults of that size; bits 3-4: 0 this header's size, 1 0.1, 2 0.2, 3 0.3, also
# the running struct's), i32 method, i32 status, name (length byte + bytes), f64 value, u32 raw size (for
# obscura_default_settings_sized and obscura_get_setting_infos_sized), edit count, edits (u8 method - 1, u8 setting
# index, u8 value selector), then the settings bytes.
METHODS = {"default": 0, "hbao": 1, "sao": 2, "lsao": 3, "ffao": 4, "reference": 5}
VERSION_BITS = {"0.4": 0, "0.1": 1 << 3, "0.2": 2 << 3, "0.3": 3 << 3}
# obscura.h's layout (64-bit): offsetof(obscura_settings, flags), sizeof(obscura_setting_info) and of its 0.3 part.
FLAGS_OFFSET = 428
SETTING_INFO_SIZE = 80
SETTING_INFO_03_SIZE = 64


def settings_seed(flags, method, status=0, name=b"", value=0.0, size=0, edits=(), overlay=b""):
    out = bytes([flags]) + struct.pack("<ii", method + 1 if flags & 6 else method, status)
    out += bytes([len(name)]) + name + struct.pack("<dI", value, size)
    out += bytes([len(edits)])
    for edit_method, index, selector in edits:
        out += bytes([edit_method - 1, index, selector])
    return out + overlay


def settings_seeds():
    seeds = {"empty": b"", "raw_zero_struct": settings_seed(0, 0)}
    for name, method in METHODS.items():
        seeds["defaults_" + name] = settings_seed(7, method)
        seeds["zero_struct_" + name] = settings_seed(3, method)
        for version in ("0.1", "0.2", "0.3"):
            seeds["defaults_%s_%s" % (name, version)] = settings_seed(7 | VERSION_BITS[version], method)
    for version in ("0.1", "0.2", "0.3"):
        seeds["zero_struct_lsao_" + version] = settings_seed(3 | VERSION_BITS[version], METHODS["lsao"])
    seeds["unknown_method"] = settings_seed(0, 42, status=-7)
    seeds["name_radius"] = settings_seed(7, METHODS["hbao"], name=b"radius", value=2.0)
    seeds["name_falloff_table"] = settings_seed(7, METHODS["reference"], name=b"falloff", value=4.0)
    seeds["name_falloff_table_array"] = settings_seed(7, METHODS["ffao"], name=b"falloff_table", value=0.5)
    seeds["name_unknown"] = settings_seed(7, METHODS["sao"], name=b"no_such_setting", value=1.0)
    seeds["name_nan"] = settings_seed(7, METHODS["lsao"], name=b"radius", value=float("nan"))
    seeds["name_enum"] = settings_seed(7, METHODS["lsao"], name=b"tangent_strategy", value=3.0)  # not the default
    # 0 where 0 is a value: in the editable form, in a zero struct (sets ZERO_IS_VALUE), in a 0.3 struct (refused).
    seeds["name_tangent_zero_defaults"] = settings_seed(7, METHODS["lsao"], name=b"tangent", value=0.0)
    seeds["name_tangent_zero_zero_struct"] = settings_seed(3, METHODS["lsao"], name=b"tangent", value=0.0)
    seeds["name_tangent_zero_0.3"] = settings_seed(7 | VERSION_BITS["0.3"], METHODS["lsao"], name=b"tangent",
                                                   value=0.0)
    seeds["name_derived_zero"] = settings_seed(7, METHODS["lsao"], name=b"directions", value=0.0)
    # A setting the caller's older struct does not have.
    seeds["name_past_0.1"] = settings_seed(7 | VERSION_BITS["0.1"], METHODS["sao"], name=b"samples", value=12.0)
    # The defaults with ZERO_IS_VALUE cleared, and with an unknown flag bit.
    seeds["defaults_lsao_flag_cleared"] = settings_seed(7, METHODS["lsao"], overlay=bytes(FLAGS_OFFSET) + b"\x01")
    seeds["defaults_hbao_unknown_flag"] = settings_seed(7, METHODS["hbao"], overlay=bytes(FLAGS_OFFSET) + b"\x02")
    # The tables in both layouts, and a size neither has.
    seeds["infos_size_current"] = settings_seed(7, METHODS["ffao"], size=SETTING_INFO_SIZE)
    seeds["infos_size_0.3"] = settings_seed(7, METHODS["ffao"], size=SETTING_INFO_03_SIZE)
    seeds["defaults_size_0.2"] = settings_seed(7, METHODS["hbao"], size=156)
    # Edits: each method's first settings at the range's edges (selectors 0 min, 1 max, 3 below, 4 above, 8 NaN).
    for name, method in list(METHODS.items())[1:]:
        seeds["edges_" + name] = settings_seed(
            7, method, edits=[(method, i, s) for i, s in zip(range(8), (0, 1, 3, 4, 8, 0, 1, 11))])
    # The smallest radius with the smallest C: the derived decay rate at its lowest (once below the minimum).
    seeds["derived_decay_rate_below_minimum"] = settings_seed(
        7, METHODS["hbao"], edits=[(METHODS["hbao"], 0, 0), (METHODS["hbao"], 1, 0)])
    # A TABLE falloff with its table written through the offset (REFERENCE rows 1 falloff, 8 falloff_table; FFAO
    # rows 1 and 14), in the running struct.
    seeds["running_reference_table"] = settings_seed(
        7, METHODS["reference"], edits=[(METHODS["reference"], 1, 1), (METHODS["reference"], 8, 1)])
    seeds["running_ffao_table_0.3"] = settings_seed(
        7 | VERSION_BITS["0.3"], METHODS["ffao"], edits=[(METHODS["ffao"], 1, 1), (METHODS["ffao"], 14, 13)])
    # LSAO tangent (row 9) and normal_threshold (row 18) set to 0 (selector 11), its preset (row 4) to its max.
    seeds["running_lsao_zeros"] = settings_seed(
        7, METHODS["lsao"], edits=[(METHODS["lsao"], 9, 11), (METHODS["lsao"], 18, 11), (METHODS["lsao"], 4, 1)])
    # Defaults with a few bytes flipped (the XOR overlay).
    seeds["defaults_ffao_flipped"] = settings_seed(7, METHODS["ffao"], overlay=bytes(8) + b"\x01\x00\x80\x3f")
    return seeds


# ---- render_fuzzer ---------------------------------------------------------------------------------------------
# Pools, as render_fuzzer.cpp's make_pools() lists them.
DEPTH = {"d32f": 0, "d24s8": 1, "d24s8_stencil_mode": 2, "d16": 3, "d32f_8x6": 4, "linear_r32f": 5,
         "d32f_1x1": 6, "d32f_33x5": 7, "linear_r16f_7x9": 8, "multisample": 9, "texture_3d": 10, "rgba8": 11,
         "buffer": 12, "deleted": 13, "zero": 14}
NORMALS = {"none": 0, "rgba16f": 1, "rgba8": 2, "rg8": 3, "rgba16f_8x6": 4, "buffer": 5, "depth": 6}
OUTPUT = {"r8": 0, "rgba16f": 1, "rgb8": 2, "r8_4x4": 3, "fbo_texture": 4, "fbo_renderbuffer": 5,
          "fbo_incomplete": 6, "default_framebuffer": 7, "never_generated_fbo": 8, "linear_depth": 9, "buffer": 10,
          "rgba32f_40x40": 11}
# Motion vectors and bent normals, as make_pools() lists them ("output", "depth", "normals", "motion": that field's
# texture in the same frame).
MOTION = {"rg16f": 0, "rg32f_large": 1, "rg32f_wild": 2, "rg16f_8x6": 3, "rg32f_33x5": 4, "rg16f_1x1": 5,
          "rg16f_7x9": 6, "rg8": 7, "rgba16f": 8, "r32f": 9, "output": 10, "depth": 11, "normals": 12, "buffer": 13,
          "deleted": 14, "texture_3d": 15, "multisample": 16}
BENT = {"rgba16f": 0, "rgba8": 1, "rgba32f_40x40": 2, "rgba16f_8x6": 3, "rgba8_1x1": 4, "r8": 5, "rg16f": 6, "rgb8": 7,
        "output": 8, "depth": 9, "normals": 10, "motion": 11, "fbo_texture": 12, "buffer": 13, "deleted": 14,
        "multisample": 15}
# decode_settings' method byte: index into {DEFAULT, HBAO, SAO, LSAO, FFAO, REFERENCE, GTAO, COUNT_}; its version
# byte: 12 0.1, 13 0.2, 14 0.3 (defaults from the 0.3 symbol), 11 0.4, 15 a raw u32 size, anything else this header's.
RENDER_METHODS = dict(METHODS, gtao=6)
SETTINGS_VERSIONS = {"0.5": 0, "0.1": 12, "0.2": 13, "0.3": 14, "0.4": 11}
# An operation's byte: the low 4 bits pick it, bit 4 the context (FRAME_FIELDS: a render's 0.5 per-frame fields
# follow its structs, decode_frame_fields); 10 with bits 5-6 = 1 creates a view, = 2 destroys one.
OPS = {"render": 0, "prepare": 8, "release": 10, "create_view": 0x2A, "destroy_view": 0x4A, "queries": 11,
       "wrong_context": 12, "render_host_error": 13, "resolve": 14, "null": 15}
SECOND_CONTEXT = 0x10
FRAME_FIELDS = 0x20
# decode_settings: an edit's row byte 192 + i is row i of obscura_get_shared_setting_infos.
SHARED = {"temporal.enabled": 192, "temporal.max_frames": 193, "temporal.clamp": 194, "temporal.plane_tolerance": 195,
          "resolution.scale": 196, "resolution.upsample_tolerance": 197}
# pick_setting_value's selectors: 0 the minimum, 1 the maximum, 7 the middle of the range (resolution.scale: HALF).
TEMPORAL_ON = (SHARED["temporal.enabled"], 1)
HALF = (SHARED["resolution.scale"], 7)
QUARTER = (SHARED["resolution.scale"], 1)


def settings_block(method, edits=(), defaults=True, version="0.5", pokes=(), shared=None):
    """edits: (setting index, value selector) pairs (192 + i: shared row i); selectors as in pick_setting_value (0 min,
    1 max, ...); shared: the byte of shared settings (bit 0 temporal on, bits 1-2 resolution.scale, bits 3-5
    temporal.max_frames 1 + 9n), which bit 7 of the version byte announces; pokes: (byte offset, u32 XORed there)
    pairs."""
    version_byte = SETTINGS_VERSIONS[version] | (0x80 if shared is not None else 0)
    out = bytes([RENDER_METHODS[method] | (0 if defaults else 8), version_byte, len(edits)])
    for index, selector in edits:
        out += bytes([index, selector])
    if shared is not None:
        out += bytes([shared])
    out += bytes([len(pokes)])
    for offset, bits in pokes:
        out += struct.pack("<HI", offset, bits)
    return out


def input_block(depth, projection=0x00, near=9, far=255, fov=128, rect=None, normals="none", units=0, layout=0,
                raw_rect=False):
    """projection: bits 0-2 < 5 perspective, 5-6 orthographic, 7 raw; 0x10 reversed-Z, 0x20 [0, 1] clip depth,
    0x40 infinite far plane. rect: 4 bytes, reduced into the texture, or with raw_rect signed bytes as they are."""
    flags = (0x40 if raw_rect else 0x20) if rect else 0x00
    out = bytes([DEPTH[depth], flags, 0])
    if rect:
        out += bytes(v & 0xFF for v in rect)
    out += bytes([projection, near, far])
    out += bytes([fov]) if (projection & 7) < 5 else bytes([fov, fov])
    out += bytes([0, layout, units])  # no perturbation
    out += bytes([0]) if normals == "none" else bytes([160, NORMALS[normals]])
    return out


def output_block(target, blend=0, view=0, position=None):
    out = bytes([OUTPUT[target], 0])
    out += bytes([160] + list(position)) if position else bytes([0])
    return out + bytes([blend, 160 + view if view else 0])


VIEWS = {"none": 0, "live": 96, "destroyed": 192, "other": 216, "never_a_view": 240}
FRAMES = {"keep": 0, "advance": 96}


def perturbation(index, how, extra=b""):
    """One entry of a matrix's perturbation: how < 96 scales entry `index` by 1 + extra/256, 96-127 scales the whole
    matrix (96: 1e30, 97: 1e-12, 98: -1, 99: 1e-30), 128 and above special_float (128 NaN, 129 +inf, 133 FLT_MAX)."""
    return bytes([index, how]) + extra


def frame_block(view="none", pick=0, frame="advance", flags=0, current=0, previous=0, camera=(0, 0, 0, 0),
                nudge=(0, 0, 0), current_perturbations=(), previous_perturbations=(), motion=None, units=0,
                bent=None, raw_flags=None):
    """The 0.5 per-frame fields (decode_frame_fields). current: 0 none, 1 projection * camera, 2 that perturbed, 3 raw;
    previous: 0 none, 1 the same, 2 the camera nudged, 3 that perturbed. camera: yaw and translation bytes (signed)."""
    out = bytes([VIEWS[view], pick, FRAMES[frame]])
    out += bytes([240]) + struct.pack("<I", raw_flags) if raw_flags is not None else bytes([192 if flags else 0])
    out += bytes([current | previous << 2]) + bytes(v & 0xFF for v in camera)
    if current == 2:
        out += bytes([len(current_perturbations) - 1]) + b"".join(current_perturbations)
    if previous >= 2:
        out += bytes(v & 0xFF for v in nudge)
    if previous == 3:
        out += bytes([len(previous_perturbations) - 1]) + b"".join(previous_perturbations)
    out += bytes([0]) if motion is None else bytes([160, MOTION[motion]])
    out += bytes([units]) if units in (0, 1) else bytes([250]) + struct.pack("<i", units)
    out += bytes([0]) if bent is None else bytes([160, BENT[bent]])
    return out


def render_op(settings, inputs, output, op="render", frame=None, context=0):
    """frame: a frame_block, which sets FRAME_FIELDS in the operation's byte; context 1: the second context."""
    code = OPS[op] | (FRAME_FIELDS if frame is not None else 0) | (SECOND_CONTEXT if context else 0)
    return bytes([code]) + settings + inputs + output + (frame or b"")


def view_op(kind, context=0, selector=0, pick=0, other_gl=False):
    """create_view, or destroy_view of the view `selector` names (0 a live one, 128 NULL, 160 a destroyed one, 192 the
    other context's, 224 a pointer that never was a view), with the other GL context current."""
    code = OPS[kind] | (SECOND_CONTEXT if context else 0)
    return bytes([code]) + (bytes([selector, pick, 224 if other_gl else 0]) if kind == "destroy_view" else b"")


def seed(*operations):
    return bytes([len(operations) - 1]) + b"".join(operations)


def render_seeds():
    seeds = {}
    for method in ("default", "hbao", "sao", "lsao", "ffao", "reference"):
        seeds["render_" + method] = seed(render_op(settings_block(method), input_block("d32f"), output_block("r8")))
    seeds["render_linear_depth_rgba16f"] = seed(
        render_op(settings_block("hbao"), input_block("linear_r32f"), output_block("rgba16f")))
    seeds["render_multisample_fbo_texture"] = seed(
        render_op(settings_block("sao"), input_block("multisample"), output_block("fbo_texture")))
    seeds["render_stencil_mode_renderbuffer_multiply"] = seed(
        render_op(settings_block("lsao"), input_block("d24s8_stencil_mode"), output_block("fbo_renderbuffer", blend=1)))
    seeds["render_reversed_infinite_d16"] = seed(
        render_op(settings_block("ffao"), input_block("d16", projection=0x50), output_block("rgba16f")))
    seeds["render_orthographic_rect"] = seed(
        render_op(settings_block("hbao"), input_block("d32f_8x6", projection=0x05, rect=(1, 1, 2, 1)),
                  output_block("r8_4x4", position=(1, 1))))
    seeds["render_normals"] = seed(
        render_op(settings_block("reference"), input_block("d32f", normals="rgba16f"), output_block("rgba16f")))
    for view in range(1, 5):
        seeds["render_debug_view_%d" % view] = seed(
            render_op(settings_block("hbao"), input_block("d24s8"), output_block("rgba16f", view=view)))
    # FFAO setting 10 is saao, on (selector 1: its max); the other fields are zero, so K becomes 18.
    seeds["render_ffao_saao"] = seed(
        render_op(settings_block("ffao", edits=[(10, 1)], defaults=False), input_block("d32f"),
                  output_block("rgba16f")))
    seeds["render_lsao_free_pattern"] = seed(  # setting 5 of LSAO is pattern: 2 (free)
        render_op(settings_block("lsao", edits=[(5, 1)]), input_block("d32f"), output_block("r8")))
    seeds["render_bad_targets"] = seed(
        render_op(settings_block("hbao"), input_block("texture_3d"), output_block("r8")),
        render_op(settings_block("hbao"), input_block("d32f"), output_block("rgb8")),
        render_op(settings_block("hbao"), input_block("d32f"), output_block("fbo_incomplete")),
        render_op(settings_block("hbao"), input_block("d32f"), output_block("default_framebuffer")))
    seeds["render_tiny_and_wide"] = seed(
        render_op(settings_block("sao"), input_block("d32f_1x1"), output_block("rgba32f_40x40")),
        render_op(settings_block("lsao"), input_block("d32f_33x5"), output_block("rgba32f_40x40")),
        render_op(settings_block("ffao"), input_block("linear_r16f_7x9"), output_block("rgba32f_40x40")))
    seeds["wrong_context"] = seed(
        render_op(settings_block("hbao"), input_block("d32f"), output_block("r8"), op="wrong_context") + bytes([0]),
        render_op(settings_block("sao"), input_block("d32f"), output_block("r8"), op="wrong_context") + bytes([1]))
    seeds["render_transposed"] = seed(
        render_op(settings_block("hbao"), input_block("d32f", layout=192), output_block("r8")))
    seeds["render_host_error"] = seed(
        render_op(settings_block("hbao"), input_block("d32f"), output_block("r8"), op="render_host_error"))
    seeds["prepare_then_render"] = seed(
        bytes([OPS["prepare"]]) + settings_block("ffao") + bytes([0, 63, 47]),
        render_op(settings_block("ffao"), input_block("d32f"), output_block("r8")))
    seeds["prepare_invalid_size"] = seed(bytes([OPS["prepare"]]) + settings_block("sao") + bytes([0x33, 0]))
    seeds["render_release_queries"] = seed(
        render_op(settings_block("sao"), input_block("d32f"), output_block("r8")),
        bytes([OPS["queries"], 16]), bytes([OPS["release"]]), bytes([OPS["queries"], 4]))
    seeds["resolve_with_context"] = seed(bytes([OPS["resolve"]]) + settings_block("hbao", edits=[(0, 4)]))
    # Settings of the older released sizes (0.3's defaults from the 0.3 symbol).
    seeds["render_hbao_settings_0.1"] = seed(
        render_op(settings_block("hbao", version="0.1"), input_block("d32f"), output_block("r8")))
    seeds["render_reference_settings_0.2"] = seed(
        render_op(settings_block("reference", version="0.2"), input_block("d32f"), output_block("rgba16f")))
    seeds["render_lsao_settings_0.3"] = seed(
        render_op(settings_block("lsao", version="0.3"), input_block("d32f"), output_block("r8")))
    seeds["render_ffao_settings_0.3"] = seed(
        render_op(settings_block("ffao", version="0.3"), input_block("d24s8"), output_block("rgba16f")))
    seeds["prepare_settings_0.2"] = seed(bytes([OPS["prepare"]]) + settings_block("sao", version="0.2") + bytes([0, 15, 11]))
    seeds["resolve_with_context_0.3"] = seed(bytes([OPS["resolve"]]) + settings_block("lsao", version="0.3"))
    # Fields refused before the GL checks: with a host GL error pending, with another GL context current. HBAO's
    # radius (offset 8) poked from 1 to infinity; an unknown flags bit (offset 428); an empty raw rectangle.
    bad_radius = settings_block("hbao", pokes=[(8, 0x40000000)])
    seeds["render_host_error_bad_settings"] = seed(
        render_op(bad_radius, input_block("d32f"), output_block("r8"), op="render_host_error"))
    seeds["render_host_error_bad_rect"] = seed(
        render_op(settings_block("hbao"), input_block("d32f", rect=(0, 0, -1, -1), raw_rect=True), output_block("r8"),
                  op="render_host_error"))
    seeds["render_unknown_settings_flag"] = seed(
        render_op(settings_block("sao", pokes=[(428, 2)]), input_block("d32f"), output_block("r8")))
    seeds["wrong_context_bad_fields"] = seed(
        render_op(bad_radius, input_block("d32f"), output_block("r8"), op="wrong_context") + bytes([0]),
        render_op(settings_block("hbao"), input_block("d32f", rect=(0, 0, -1, -1), raw_rect=True), output_block("r8"),
                  op="wrong_context") + bytes([0]),
        render_op(bad_radius, input_block("d32f"), output_block("r8"), op="wrong_context") + bytes([1]))
    seeds["null_arguments"] = seed(bytes([OPS["null"]]) + settings_block("hbao") + bytes([1]))
    seeds.update(frame_field_seeds())
    return seeds


def frame_field_seeds():
    """The 0.5 per-frame fields and views: GTAO with bent normals, temporal sequences (matrices, motion vectors, views,
    camera cuts), reduced resolution, and the refusals (views, flags, matrices, motion vectors, bent normals)."""
    seeds = {}
    d32f, rgba16f = input_block("d32f"), output_block("rgba16f")
    camera = (12, 20, -8, 40)
    moving = dict(current=1, previous=2, camera=camera, nudge=(3, 4, -2))
    seeds["render_gtao"] = seed(render_op(settings_block("gtao"), d32f, output_block("r8")))
    seeds["render_gtao_bent_normals"] = seed(
        render_op(settings_block("gtao"), d32f, rgba16f, frame=frame_block(bent="rgba16f")))
    seeds["render_gtao_bent_normals_offset_rgba32f"] = seed(
        render_op(settings_block("gtao"), input_block("d32f_33x5", normals="none"),
                  output_block("rgba32f_40x40", position=(3, 2)), frame=frame_block(bent="rgba32f_40x40")))
    seeds["render_gtao_bent_normals_half"] = seed(
        render_op(settings_block("gtao", edits=[HALF]), input_block("d24s8", normals="rgba16f"), rgba16f,
                  frame=frame_block(bent="rgba16f")),
        render_op(settings_block("gtao", edits=[HALF]), d32f, output_block("rgba16f", view=3),
                  frame=frame_block(bent="rgba8")))
    seeds["render_bent_normals_refused"] = seed(
        render_op(settings_block("hbao"), d32f, rgba16f, frame=frame_block(bent="rgba16f")),          # not GTAO
        render_op(settings_block("gtao"), d32f, rgba16f, frame=frame_block(bent="output")),           # aliases
        render_op(settings_block("gtao"), d32f, rgba16f, frame=frame_block(bent="rgba16f_8x6")),      # too small
        render_op(settings_block("gtao"), d32f, output_block("fbo_texture"), frame=frame_block(bent="fbo_texture")))
    # Temporal accumulation over a view's frames: matrices of a moving camera, then motion vectors.
    temporal = settings_block("hbao", edits=[TEMPORAL_ON])
    seeds["temporal_view_matrices"] = seed(
        view_op("create_view"),
        *[render_op(temporal, d32f, rgba16f, frame=frame_block(view="live", pick=255, **moving)) for _ in range(3)])
    seeds["temporal_motion_vectors"] = seed(
        *[render_op(settings_block("gtao", edits=[TEMPORAL_ON]), d32f, rgba16f,
                    frame=frame_block(current=1, previous=1, camera=camera, motion=m, units=u, bent="rgba16f"))
          for m, u in (("rg16f", 0), ("rg32f_large", 1), ("rg32f_wild", 0), ("rg16f", 0))])
    seeds["temporal_reset_and_debug_view"] = seed(
        render_op(settings_block("sao", edits=[TEMPORAL_ON, (SHARED["temporal.max_frames"], 0)]), d32f, rgba16f,
                  frame=frame_block(**moving)),
        render_op(settings_block("sao", edits=[TEMPORAL_ON]), d32f, output_block("rgba16f", view=1),
                  frame=frame_block(**moving)),
        render_op(settings_block("sao", edits=[TEMPORAL_ON]), d32f, rgba16f, frame=frame_block(flags=1, **moving)),
        render_op(settings_block("sao", edits=[TEMPORAL_ON]), d32f, output_block("rgba16f", blend=1),
                  frame=frame_block(frame="keep", **moving)))
    # The same through the shared-settings byte: temporal on (bit 0), half (2 << 1) or quarter (3 << 1), max_frames.
    seeds["temporal_reduced_lsao_ffao"] = seed(
        render_op(settings_block("lsao", shared=1 | 2 << 1), d32f, rgba16f, frame=frame_block(**moving)),
        render_op(settings_block("ffao", shared=1 | 3 << 1 | 2 << 3), d32f, rgba16f, frame=frame_block(**moving)),
        render_op(settings_block("reference", shared=1 | 2 << 1), d32f, rgba16f, frame=frame_block(**moving)),
        render_op(settings_block("gtao", shared=1 | 2 << 1), input_block("d32f_33x5"), output_block("rgba32f_40x40"),
                  frame=frame_block(current=1, previous=1, camera=camera, motion="rg32f_33x5")))
    # Matrices that are valid but extreme: scaled by 1e30, one entry a little off.
    seeds["temporal_extreme_matrices"] = seed(
        render_op(temporal, d32f, rgba16f, frame=frame_block(current=2, previous=1, camera=camera,
                                                             current_perturbations=[perturbation(0, 96)])),
        render_op(temporal, d32f, rgba16f, frame=frame_block(current=1, previous=3, camera=camera,
                                                             previous_perturbations=[perturbation(12, 5, b"\x40")])))
    # Reduced resolution alone, odd sizes and a target offset.
    seeds["reduced_resolution"] = seed(
        render_op(settings_block("hbao", edits=[HALF]), d32f, rgba16f),
        render_op(settings_block("sao", edits=[QUARTER]), input_block("d32f_33x5"), output_block("rgba32f_40x40",
                                                                                                 position=(5, 7))),
        render_op(settings_block("gtao", edits=[QUARTER]), input_block("d32f_1x1"), rgba16f),
        render_op(settings_block("ffao", edits=[HALF]), input_block("linear_r16f_7x9"), rgba16f))
    # Views: a destroyed one, the other context's, a pointer that never was one; destroying them.
    seeds["views_refused"] = seed(
        view_op("create_view"), view_op("destroy_view", selector=0),
        render_op(temporal, d32f, rgba16f, frame=frame_block(view="destroyed", **moving)),
        render_op(temporal, d32f, rgba16f, frame=frame_block(view="never_a_view")))
    seeds["views_of_the_other_context"] = seed(
        view_op("create_view", context=1),
        render_op(temporal, d32f, rgba16f, frame=frame_block(view="other")),
        view_op("destroy_view", selector=192),
        view_op("destroy_view", context=1, selector=0, other_gl=True))
    seeds["views_refused_before_host_state"] = seed(
        render_op(temporal, d32f, rgba16f, op="render_host_error", frame=frame_block(view="never_a_view")),
        render_op(temporal, d32f, rgba16f, op="wrong_context", frame=b"\x00" + frame_block(view="never_a_view")),
        view_op("destroy_view", selector=224), view_op("destroy_view", selector=128))
    # Fields refused: unknown flag bits, a non-finite or singular matrix, motion vectors of the wrong kind.
    seeds["frame_fields_refused"] = seed(
        render_op(temporal, d32f, rgba16f, frame=frame_block(raw_flags=2)),
        render_op(temporal, d32f, rgba16f,
                  frame=frame_block(current=1, previous=3, camera=camera,
                                    previous_perturbations=[perturbation(5, 128)])),
        render_op(temporal, d32f, rgba16f,
                  frame=frame_block(current=2, previous=1, camera=camera, current_perturbations=[perturbation(0, 99)])),
        render_op(temporal, d32f, rgba16f, frame=frame_block(units=7)))
    seeds["motion_vectors_refused"] = seed(
        *[render_op(temporal, d32f, rgba16f, frame=frame_block(current=1, previous=2, camera=camera, motion=m))
          for m in ("rg16f_8x6", "rgba16f", "output", "multisample")])
    return seeds


def write(target, seeds):
    directory = os.path.join(HERE, "corpus", target)
    os.makedirs(directory, exist_ok=True)
    for name in os.listdir(directory):
        os.remove(os.path.join(directory, name))
    for name, data in sorted(seeds.items()):
        with open(os.path.join(directory, name), "wb") as f:
            f.write(data)
    print("%s: %d seeds in %s" % (target, len(seeds), os.path.relpath(directory)))


if __name__ == "__main__":
    write("settings_fuzzer", settings_seeds())
    write("render_fuzzer", render_seeds())
