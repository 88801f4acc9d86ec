#!/usr/bin/env python3
"""Writes the hand-made seed inputs of the fuzz targets into tests/fuzz/corpus/<target>/.

Each seed is a short byte string in the layout the target's LLVMFuzzerTestOneInput decodes (documented at the
top of settings_fuzzer.cpp and in render_fuzzer.cpp's decode_* functions); missing bytes read as zero, so a seed
only spells out what differs from zero. Run it again after changing a decoder:

    python3 tests/fuzz/make_seeds.py

The seeds give the fuzzer a successful call of every kind to mutate from: default settings of every method,
renders of every method from every depth format into every target kind, prepare, the queries, a host GL error
and NULL arguments.
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# ---- settings_fuzzer -------------------------------------------------------------------------------------------
# flags (bit 0: valid struct_size, bit 1: small method (method % 8 - 1) into the struct, bit 2: XOR onto that
# method's defaults), i32 method, i32 status, name (length byte + bytes), f64 value, edit count, edits
# (u8 method - 1, u8 setting index, u8 value selector), then the settings bytes.
METHODS = {"default": 0, "hbao": 1, "sao": 2, "lsao": 3, "ffao": 4, "reference": 5}


def settings_seed(flags, method, status=0, name=b"", value=0.0, edits=(), overlay=b""):
    out = bytes([flags]) + struct.pack("<ii", method + 1 if flags & 6 else method, status)
    out += bytes([len(name)]) + name + struct.pack("<d", value)
    out += bytes([len(edits)])
    for edit_method, index, selector in edits:
        out += bytes([edit_method - 1, index, selector])
    return out + overlay


def settings_seeds():
    seeds = {"empty": b"", "raw_zero_struct": settings_seed(0, 0)}
    for name, method in METHODS.items():
        seeds["defaults_" + name] = settings_seed(7, method)
        seeds["zero_struct_" + name] = settings_seed(3, method)
    seeds["unknown_method"] = settings_seed(0, 42, status=-7)
    seeds["name_radius"] = settings_seed(7, METHODS["hbao"], name=b"radius", value=2.0)
    seeds["name_falloff_table"] = settings_seed(7, METHODS["reference"], name=b"falloff", value=4.0)
    seeds["name_unknown"] = settings_seed(7, METHODS["sao"], name=b"no_such_setting", value=1.0)
    seeds["name_nan"] = settings_seed(7, METHODS["lsao"], name=b"radius", value=float("nan"))
    # Edits: each method's first settings at the range's edges (selectors 0 min, 1 max, 3 below, 4 above, 8 NaN).
    for name, method in list(METHODS.items())[1:]:
        seeds["edges_" + name] = settings_seed(
            7, method, edits=[(method, i, s) for i, s in zip(range(8), (0, 1, 3, 4, 8, 0, 1, 11))])
    # The smallest radius with the smallest C: the derived decay rate falls below its minimum (a known issue that
    # settings_fuzzer.cpp tolerates; see kTolerateDerivedDecayRateBelowMinimum).
    seeds["derived_decay_rate_below_minimum"] = settings_seed(
        7, METHODS["hbao"], edits=[(METHODS["hbao"], 0, 0), (METHODS["hbao"], 1, 0)])
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
# decode_settings' method byte: index into {DEFAULT, HBAO, SAO, LSAO, FFAO, REFERENCE, COUNT_, -1}.
OPS = {"render": 0, "prepare": 8, "release": 10, "queries": 11, "wrong_context": 12, "render_host_error": 13,
       "resolve": 14, "null": 15}


def settings_block(method, edits=(), defaults=True):
    """edits: (setting index, value selector) pairs; selectors as in pick_setting_value (0 min, 1 max, ...)."""
    out = bytes([METHODS[method] | (0 if defaults else 8), len(edits)])
    for index, selector in edits:
        out += bytes([index, selector])
    return out + bytes([0, 0])  # no pokes, struct_size valid


def input_block(depth, projection=0x00, near=9, far=255, fov=128, rect=None, normals="none", units=0, layout=0):
    """projection: bits 0-2 < 5 perspective, 5-6 orthographic, 7 raw; 0x10 reversed-Z, 0x20 [0, 1] clip depth,
    0x40 infinite far plane."""
    flags = 0x20 if rect else 0x00
    out = bytes([DEPTH[depth], flags, 0])
    if rect:
        out += bytes(rect)
    out += bytes([projection, near, far])
    out += bytes([fov]) if (projection & 7) < 5 else bytes([fov, fov])
    out += bytes([0, layout, units])  # no perturbation
    out += bytes([0]) if normals == "none" else bytes([160, NORMALS[normals]])
    return out


def output_block(target, blend=0, view=0, position=None):
    out = bytes([OUTPUT[target], 0])
    out += bytes([160] + list(position)) if position else bytes([0])
    return out + bytes([blend, 160 + view if view else 0])


def render_op(settings, inputs, output, op="render"):
    return bytes([OPS[op]]) + settings + inputs + output


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
    seeds["null_arguments"] = seed(bytes([OPS["null"]]) + settings_block("hbao") + bytes([1]))
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
