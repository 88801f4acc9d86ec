#!/usr/bin/env bash
# Generates the parameter guide, docs/parameters.md, and its pictures, docs/images/parameters/*.png:
# every setting of every available method, what it does to the picture and what it costs.
#
# The settings (names, types, defaults, ranges, units, descriptions) come from the SDK's metadata through
# `obscura --list-settings METHOD`, the methods from `obscura --list-methods`; the values shown are picked
# from that metadata by the rules in pick_values() below. Each setting is one `obscura compare --truth both`
# run with the method's spec at each value on the atrium at 320x180 (the geometry truth with 256 rays, the
# screen-space reference with 64): its --strip sheet becomes docs/images/parameters/<method>_<setting>.png and
# its --json report the table of cost and error against each.
#
# Usage:  scripts/parameter-guide.sh
#   OBSCURA_BIN     the CLI to run (default: build/bin/obscura of this checkout; needs `compare --strip`)
#   GUIDE_SIZE      image size (default 320x180)      GUIDE_RAYS   screen-space reference rays per pixel (default 64)
#   GUIDE_TRUTH_RAYS  geometry truth rays per pixel (default 256)
#   GUIDE_METHODS   space-separated subset of the methods, for a quick look (default: every available one)
#   GUIDE_ONLY      one setting's name: only its section (and the method's defaults), to splice into the guide
# Needs jq and awk. Without a GPU: EGL_PLATFORM=surfaceless LIBGL_ALWAYS_SOFTWARE=1 (Mesa llvmpipe), where
# the whole guide takes 17-19 minutes on 2 cores (with other work beside it). The documents are replaced
# only when every run succeeded.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${OBSCURA_BIN:-${OBSCURA_BUILD_DIR:-$root/build}/bin/obscura}"
size="${GUIDE_SIZE:-320x180}"
rays="${GUIDE_RAYS:-64}"
truth_rays="${GUIDE_TRUTH_RAYS:-256}"
scene="atrium"
doc="$root/docs/parameters.md"
image_dir="$root/docs/images/parameters"

die() {
  echo "parameter-guide: $*" >&2
  exit 1
}

[[ -x "$bin" ]] || die "no obscura CLI at '$bin' (build it with 'scripts/build.sh obscura_cli' or set OBSCURA_BIN)"
command -v jq >/dev/null || die "needs jq (apt-get install jq)"
[[ "$("$bin" --help)" == *"--strip"* ]] || die "'$bin' has no 'compare --strip': rebuild the CLI"
[[ "$size" =~ ^[0-9]+x[0-9]+$ ]] || die "GUIDE_SIZE '$size' is not WxH"
[[ "$rays" =~ ^[0-9]+$ ]] || die "GUIDE_RAYS '$rays' is not a number"
[[ "$truth_rays" =~ ^[0-9]+$ ]] || die "GUIDE_TRUTH_RAYS '$truth_rays' is not a number"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/images"
started=$SECONDS
load_start="$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo "?")"

# ---- Overrides --------------------------------------------------------------------------------------
# Settings that act only when another one is set: every value of the setting is rendered with these
# (compare --set).
declare -A context=(
  [lsao.step_length]="pattern=2"             # the free pattern walks D_S itself; the aligned ones whole template steps
  [lsao.warmup_tolerance]="segment_steps=16" # segments only; on CPU renderers the default sweeps whole lines
  [lsao.warmup_stride]="segment_steps=16"
  [lsao.normal_threshold]="normal_test=on"
  [ffao.saao_blur]="saao=on"
  [lsao.tangent]="tangent_strategy=fixed"  # the receiver's tangent (the default) does not read it; fixed_hull does
  [gtao.thickness]="thickness_mode=bitmask"  # horizon mode's occluders are infinitely thick
  [gtao.sectors]="thickness_mode=bitmask"
)
# What the guide says of an override where "the setting acts only with it" is not the whole story.
declare -A context_note=(
  [lsao.step_length]="Rendered with \`pattern=2\` (free) for every value: there D_S is the value itself; with the aligned patterns (the
default) the setting acts in whole template steps only (at K = 8, 1.41 px each), so values that round to the same
number of steps render alike."
  [lsao.tangent]="Rendered with \`tangent_strategy=fixed\` for every value: the setting acts with it (hull and occlusion) and with
\`fixed_hull\` (the hull's only), not with the receiver's tangent (the default)."
)
# Values where the automatic rule gives a useless picture.
declare -A fixed_values=(
  # At 320x180 a 1 m radius rarely spans 64 px: the automatic 64, 256, 1024 look the same.
  [hbao.max_radius_pixels]="8 32 256"
  [sao.max_radius_pixels]="8 32 256"
  [gtao.max_radius_pixels]="8 32 256"
  # The aligned pattern needs multiples of 8; the automatic low value (4) is refused.
  [lsao.directions]="8 16 32"
  # Automatic -1, 0, 4096: 0 is -1 (whole lines) on CPU renderers and no line is 4096 steps long.
  [lsao.segment_steps]="0 16 128"
  # The range's end (10000 m) is as thick as 0 (infinitely thick).
  [ffao.thickness]="0 0.1 0.5"
  [reference.thickness]="0 0.1 0.5"
  # 4 (table) needs falloff_table, a table of its own: explained in the text.
  [ffao.falloff]="1 2 3"
  [reference.falloff]="1 2 3"
)
# Settings explained in text only, and notes added below a setting's table.
declare -A text_only=(
  [reference.first_ray]="It only offsets each pixel's ray sequence, so a host can accumulate frames rendered with first_ray = 0, rays, 2 rays ... into one converged image: a single picture at another first_ray is the same picture with other noise (its error is the noise of \`rays\` rays, see \`rays\` above), and the cost does not depend on it."
)
declare -A notes=(
  [ffao.falloff]="Not shown: 4 (table), the falloff \`falloff_table[i]\` = rho(i/(N-1) radius) given in \`obscura_settings.ffao.falloff_table\` (linear in between, 0 beyond the radius); a spec gives it as \`ffao:falloff=table:falloff_table=V0/V1/.../V15\` or \`falloff_table=@FILE\` (\`falloff=table\` without it is refused). It costs what the other falloffs cost."
  [reference.falloff]="Not shown: 4 (table), \`obscura_settings.reference.falloff_table\`, given as FFAO's is (see FFAO's \`falloff\`)."
  [ffao.frame_split]="One frame each, without accumulation: the pictures show the 2x2 pattern of the orientations' shares. With \`temporal.enabled\` a still view converges to the image of every orientation (below the default's error after 16 frames at 4, for 0.29-0.36x of its cost at 1280x720: docs/quality.md, \"Temporal presets\")."
)

# ---- Metadata ---------------------------------------------------------------------------------------
# `--list-settings METHOD` prints left-aligned columns whose widths are in its header line; a value wider
# than its column pushes the rest right, and the unit may be empty. Prints one line per setting:
# name, type, default, min, max, unit, description separated by \x1f (so empty fields survive `read`).
list_settings() {
  "$bin" --list-settings "$1" | awk -v method="$1" '
    function fail(text) { print "bad --list-settings " method " line " NR ": " text > "/dev/stderr"; bad = 1; exit 1 }
    NR == 1 { next }
    /^ +name +type +default +min +max +unit +description$/ {
      split("name type default min max unit description", columns, " ")
      for (i = 1; i <= 7; ++i) start[i] = index($0, " " columns[i] (i < 7 ? " " : "")) + 1
      for (i = 1; i <= 6; ++i) width[i] = start[i + 1] - start[i] - 1
      header = 1
      next
    }
    /^ *$/ { next }
    /\(no settings\)/ { next }
    {
      if (!header) fail("no header line before the settings")
      position = start[1]
      for (i = 1; i <= 6; ++i) {
        rest = substr($0, position)
        field[i] = (substr(rest, 1, 1) == " ") ? "" : substr(rest, 1, match(rest " ", / /) - 1)
        if (field[i] == "" && i != 6) fail("empty " columns[i])
        position += (length(field[i]) > width[i] ? length(field[i]) : width[i]) + 1
      }
      if (field[2] !~ /^(float|int|toggle|enum|float\[[0-9]+\])$/) fail("type " field[2])
      for (i = 4; i <= 5; ++i) if (field[i] !~ /^-?[0-9.]+(e[-+][0-9]+)?$/) fail(columns[i] " " field[i])
      printf "%s\x1f%s\x1f%s\x1f%s\x1f%s\x1f%s\x1f%s\n", field[1], field[2], field[3], field[4], field[5], field[6], substr($0, position)
    }
    END { if (!bad && !header) { print "no settings header from --list-settings " method > "/dev/stderr"; exit 1 } }'
}

# The values to show of a setting: TYPE DEFAULT MIN MAX EFFECTIVE (the resolved default: the value of a
# "derived" setting, e.g. HBAO's decay rate C*radius^2, and an enum's number).
#   toggle: off, on
#   enum: as an int (by number)
#   int with at most 6 values in its range: every value; other ints: default/4, default, default*4
#     (rounded, clamped to the range), or min, default, max when the default is the minimum or below 1
#   float: default/4, default, default*4 clamped to the range; min, default, max when the range is tiny
#     (it reaches 0 or below, or spans at most 16x); min, a tenth of the range, max when the default is 0
pick_values() {
  awk -v type="$1" -v def="$2" -v low="$3" -v high="$4" -v eff="$5" '
    function clamp(x) { return x < low ? low : (x > high ? high : x) }
    function add(x,    text) {
      text = (type == "int" || type == "enum") ? sprintf("%d", x) : sprintf("%.6g", x)
      if (!(text in seen)) { seen[text] = 1; list = list (list == "" ? "" : " ") text }
    }
    BEGIN {
      if (type == "toggle") { print "off on"; exit }
      low += 0; high += 0; d = eff + 0
      if (type == "int" || type == "enum") {
        if (high - low + 1 <= 6) { for (v = low; v <= high; ++v) add(v) }
        else if (d <= low || d < 1) { add(low); add(d); add(high) }
        else { add(clamp(int(d / 4 + 0.5))); add(d); add(clamp(d * 4)) }
      } else if (d == 0) { add(low); add(low + (high - low) / 10); add(high) }
      else if (low <= 0 || high <= 16 * low) { add(low); add(d); add(high) }
      else { add(clamp(d / 4)); add(d); add(clamp(d * 4)) }
      print list
    }'
}

same_number() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 == b + 0) }'; }

# ---- Runs -------------------------------------------------------------------------------------------
methods=()
while read -r name state _; do
  if [[ "$state" == "available" ]]; then methods+=("$name"); fi
done < <("$bin" --list-methods)
((${#methods[@]})) || die "'$bin --list-methods' lists no available method"
if [[ -n "${GUIDE_METHODS:-}" ]]; then
  for method in $GUIDE_METHODS; do
    [[ " ${methods[*]} " == *" $method "* ]] || die "GUIDE_METHODS: '$method' is not an available method (${methods[*]})"
  done
  read -r -a methods <<<"$GUIDE_METHODS"
fi
unavailable="$("$bin" --list-methods | awk '$2 != "available" { print $1 }' | paste -sd, -)"

gl_line=""
body="$work/body.md"
: >"$body"
runs=0

for method in "${methods[@]}"; do
  list_settings "$method" >"$work/$method.settings" || die "cannot read the settings of $method from '$bin --list-settings $method'"
  echo "parameter-guide: $method: $(wc -l <"$work/$method.settings") settings" >&2

  # The reference against itself: its settings are rendered at $rays rays and measured against its own
  # default ray count; everything else against a $rays-ray reference.
  reference_rays="$rays"
  if [[ "$method" == "reference" ]]; then
    reference_rays="$(awk -F'\x1f' '$1 == "rays" { print $3 }' "$work/$method.settings")"
    [[ -n "$reference_rays" ]] || die "the reference has no 'rays' setting"
  fi

  # The method at its defaults: the section's first pictures, and its effective settings (derived
  # defaults resolved) from the JSON report.
  echo "parameter-guide: $method at its defaults" >&2
  rm -rf "$work/out"
  "$bin" compare --scene "$scene" --size "$size" --truth both --truth-rays "$truth_rays" \
    --reference-rays "$reference_rays" --methods "$method" \
    --out-dir "$work/out" --json "$work/$method.defaults.json" </dev/null >"$work/compare.log" 2>&1 ||
    die "compare of $method at its defaults failed: $(tail -n 3 "$work/compare.log")"
  runs=$((runs + 1))
  [[ -n "$gl_line" ]] || gl_line="$(sed -n 's/^GL: //p' "$work/compare.log" | head -n 1)"
  cp "$work/out/1_$method.png" "$work/images/${method}_defaults.png"
  cp "$work/out/geometry_truth_1.png" "$work/images/${method}_truth.png"
  [[ "$method" == "reference" ]] || cp "$work/out/reference_1.png" "$work/images/${method}_reference.png"
  read -r gpu wall mean signed within screen_mean screen_within falloff < <(jq -r '.methods[0] as $m |
    [$m.gpu_ms.total, $m.wall_ms, $m.errors.geometry.mean_abs, $m.errors.geometry.signed_mean,
     $m.errors.geometry.within_5pct, $m.errors.screen.mean_abs, $m.errors.screen.within_5pct,
     .truths[1].references[0].falloff] | @tsv' "$work/$method.defaults.json")

  {
    echo
    echo "## $method"
    echo
    if [[ "$method" == "reference" ]]; then
      echo "![reference at its defaults](images/parameters/${method}_defaults.png) ![the geometry truth](images/parameters/${method}_truth.png)"
      echo
      echo "The screen-space reference at its defaults (left: $falloff, $reference_rays rays, $(awk -v w="$wall" 'BEGIN { printf "%.0f", w }') ms) and the geometry"
      awk -v e="$mean" -v s="$signed" -v p="$within" -v t="$truth_rays" 'BEGIN {
        printf "truth with its falloff (right, %d rays): against the truth mean_abs %.4f, signed %+.4f, within_5pct %.1f %%.\n", t, e, s, 100 * p }'
      echo "Below, every setting but \`rays\` is rendered with \`rays=$rays\`; the screen columns measure it against the"
      echo "reference with the same settings at its default $reference_rays rays, so their error is only the noise of $rays"
      echo "rays, and the cost is that of $rays rays (it grows with the rays; one frame, not the median of 5). The"
      echo "geometry columns say how far each setting brings the screen-space reference from the geometry (\`thickness\`"
      echo "most). The other methods' screen-space references in this guide have $rays rays."
    else
      echo "![$method at its defaults](images/parameters/${method}_defaults.png) ![the geometry truth](images/parameters/${method}_truth.png) ![the screen-space reference](images/parameters/${method}_reference.png)"
      echo
      awk -v m="$method" -v g="$gpu" -v w="$wall" -v e="$mean" -v s="$signed" -v p="$within" -v se="$screen_mean" \
          -v sp="$screen_within" -v f="$falloff" -v r="$rays" -v t="$truth_rays" 'BEGIN {
        printf "%s at its defaults (left), the geometry truth it is measured against (middle: %s, %d rays) and the\n", m, f, t
        printf "screen-space reference with the same falloff (right, %d rays): gpu %.1f ms, wall %.1f ms; against the\n", r, g, w
        printf "geometry truth mean_abs %.4f, signed %+.4f, within_5pct %.1f %%; against the screen-space reference\n", e, s, 100 * p
        printf "mean_abs %.4f, within_5pct %.1f %%.\n", se, 100 * sp }'
      echo "In the strips below every tile is $method at its defaults but for the one setting, measured against these"
      echo "truths, or against one per value where the setting changes the falloff."
    fi
  } >>"$body"

  while IFS=$'\x1f' read -r name type default min max unit description; do
    [[ -z "${GUIDE_ONLY:-}" || "$name" == "$GUIDE_ONLY" ]] || continue
    key="$method.$name"
    # The shared settings (every method has them): the temporal ones act across frames, which one still picture
    # cannot show, and the upsample's tolerance only at reduced resolution.
    if [[ "$name" == temporal.* && -z "${text_only[$key]:-}" ]]; then
      text_only[$key]="It acts across frames (the accumulation of a view's history), which one still picture cannot show: docs/quality.md measures it under an orbit and on the moving scene (\`obscura compare --frames N --orbit DEG --temporal on\`; the sliding scene for the ghosting)."
    fi
    if [[ "$name" == "resolution.upsample_tolerance" && -z "${context[$key]:-}" ]]; then
      context[$key]="resolution.scale=half"
    fi
    effective="$(jq -r --arg name "$name" '.methods[0].settings[$name] | if . == true then "on" elif . == false then "off" elif . == null then "" else tostring end' "$work/$method.defaults.json")"
    [[ -n "$effective" ]] || effective="$default"
    unit_text="${unit:+ $unit}"
    range="$min to $max$unit_text"
    [[ "$type" == "toggle" ]] && range="off or on"
    default_text="$default$unit_text"
    if [[ "$default" == "derived" ]]; then
      default_text="derived (here $effective$unit_text)"
    elif [[ "$type" == "enum" ]]; then
      default_text="$default ($effective)"
    elif [[ "$type" != "toggle" && "$effective" != "$default" ]] && ! same_number "$effective" "$default"; then
      default_text="$default$unit_text (resolved here: $effective$unit_text)"
    fi
    {
      echo
      echo "### \`$name\`"
      echo
      echo "${description//|/\\|}"
      echo
      echo "$type, ${range}; default ${default_text}."
    } >>"$body"

    if [[ -n "${text_only[$key]:-}" ]]; then
      printf '\n%s\n' "Not rendered. ${text_only[$key]}" >>"$body"
      continue
    fi
    if [[ "$type" == float\[* ]]; then
      printf '\n%s\n' "Not rendered: an array (the falloff table), read only with \`falloff=table\` (see \`falloff\`)." >>"$body"
      continue
    fi

    values="${fixed_values[$key]:-}"
    [[ -n "$values" ]] || values="$(pick_values "$type" "$default" "$min" "$max" "$effective")"
    specs=()
    for value in $values; do specs+=("$method:$name=$value"); done
    spec_list="$(IFS=,; echo "${specs[*]}")"
    arguments=(compare --scene "$scene" --size "$size" --truth both --truth-rays "$truth_rays"
               --reference-rays "$reference_rays" --methods "$spec_list")
    shown_context="${context[$key]:-}"
    [[ "$method" == "reference" && "$name" != "rays" ]] && shown_context="rays=$rays${shown_context:+ $shown_context}"
    for setting in $shown_context; do arguments+=(--set "$setting"); done
    image="${method}_${name}.png"

    echo "parameter-guide: $method $name: $values${shown_context:+ (with $shown_context)}" >&2
    rm -rf "$work/out"
    if ! "$bin" "${arguments[@]}" --out-dir "$work/out" --json "$work/report.json" --strip "$work/images/$image" \
      </dev/null >"$work/compare.log" 2>&1; then
      tail -n 5 "$work/compare.log" >&2
      die "compare failed for $method setting '$name' ($bin ${arguments[*]})"
    fi
    runs=$((runs + 1))

    # One row per value: value, gpu ms, wall ms, against the geometry truth mean_abs, signed, within_5pct,
    # against the screen-space reference mean_abs, within_5pct, and the falloff. The falloff's description
    # leaves out a derived decay rate (C*radius^2), so where falloffs of one description differ in it (C of
    # a falloff other than rho0) it is added.
    jq -r '.truths[1].references as $refs | .methods[] | $refs[.falloff - 1] as $ref |
           [(.method | sub("^[^:]*:[^=]*="; "")), .gpu_ms.total, .wall_ms, .errors.geometry.mean_abs,
            .errors.geometry.signed_mean, .errors.geometry.within_5pct, .errors.screen.mean_abs,
            .errors.screen.within_5pct,
            (if ([$refs[] | select(.falloff == $ref.falloff) | .settings.decay_rate] | unique | length) > 1
             then "\($ref.falloff) decay=\($ref.settings.decay_rate) m^2" else $ref.falloff end)] | @tsv' \
      "$work/report.json" >"$work/rows.tsv"
    default_wall=""
    while IFS=$'\t' read -r value _ wall _; do
      if [[ "$value" == "$effective" ]] || { [[ "$type" != "toggle" ]] && same_number "$value" "$effective"; }; then
        default_wall="$wall"
      fi
    done <"$work/rows.tsv"

    {
      echo
      if [[ -n "${context_note[$key]:-}" ]]; then
        echo "${context_note[$key]}"
        echo
      elif [[ -n "${context[$key]:-}" ]]; then
        echo "Rendered with \`${context[$key]}\` for every value: the setting acts only with it."
        echo
      fi
      echo "![$method $name: ${values// /, }](images/parameters/$image)"
      echo
      echo "| $name | gpu ms | wall ms | wall vs default | truth: mean_abs | signed | within_5pct | screen ref: mean_abs | within_5pct | falloff |"
      echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"
      while IFS=$'\t' read -r value gpu wall mean signed within screen_mean screen_within falloff; do
        label="$value"
        ratio="-"
        if [[ -n "$default_wall" ]]; then
          ratio="$(awk -v a="$wall" -v b="$default_wall" 'BEGIN { printf "%.2fx", a / b }')"
        fi
        if [[ "$value" == "$effective" ]] || { [[ "$type" != "toggle" ]] && same_number "$value" "$effective"; }; then
          label="**$value** (default)"
        fi
        awk -v label="$label" -v gpu="$gpu" -v wall="$wall" -v ratio="$ratio" -v mean="$mean" -v signed="$signed" \
          -v within="$within" -v smean="$screen_mean" -v swithin="$screen_within" -v falloff="$falloff" 'BEGIN {
          printf "| %s | %.1f | %.1f | %s | %.4f | %+.4f | %.1f %% | %.4f | %.1f %% | %s |\n", label, gpu, wall, ratio, mean,
                 signed, 100 * within, smean, 100 * swithin, falloff }'
      done <"$work/rows.tsv"
      echo
      echo "\`obscura ${arguments[*]} --strip $image\`"
      [[ -z "${notes[$key]:-}" ]] || printf '\n%s\n' "${notes[$key]}"
    } >>"$body"
  done <"$work/$method.settings"
done

# ---- The document -----------------------------------------------------------------------------------
elapsed=$((SECONDS - started))
load_end="$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo "?")"
command_line="scripts/parameter-guide.sh"
[[ -z "${OBSCURA_BIN:-}" ]] || command_line="OBSCURA_BIN=$OBSCURA_BIN $command_line"
[[ -z "${GUIDE_SIZE:-}" ]] || command_line="GUIDE_SIZE=$GUIDE_SIZE $command_line"
[[ -z "${GUIDE_RAYS:-}" ]] || command_line="GUIDE_RAYS=$GUIDE_RAYS $command_line"
[[ -z "${GUIDE_METHODS:-}" ]] || command_line="GUIDE_METHODS=\"$GUIDE_METHODS\" $command_line"
software=""
[[ "$gl_line" =~ llvmpipe|softpipe ]] && software=1
{
  echo "# Parameter guide"
  echo
  echo "<!-- Generated by scripts/parameter-guide.sh: do not edit; change the SDK's metadata or the script and rerun it. -->"
  echo
  echo "Every setting of every method: what it does to the picture and what it costs. Generated by"
  echo "\`scripts/parameter-guide.sh\` (do not edit by hand) on $(date -u +%Y-%m-%d) with"
  echo
  echo "    $command_line"
  echo
  echo "- GL: ${gl_line:-unknown}."
  echo "- ${runs} \`obscura compare\` runs in $((elapsed / 60)) min $((elapsed % 60)) s on $(nproc) cores (load average $load_start at the"
  echo "  start, $load_end at the end)."
  echo "- Scene: the built-in \`$scene\` (default viewpoint) at $size, +10 % guard band; the geometry truth with $truth_rays rays"
  echo "  per pixel, the screen-space references with $rays."
  echo "- Settings, defaults, ranges, units and descriptions: \`obscura --list-settings METHOD\` (the SDK's"
  echo "  \`obscura_get_setting_infos\`). The values shown follow the rules of the script's pick_values(): toggles off and"
  echo "  on; integers with at most 6 values all of them, others a quarter of the default, the default and four"
  echo "  times it; floats the same, or the range's ends where the range is small or the default is 0. A few"
  echo "  settings use values of their own or need another setting to act; the text under them says so."
  [[ -z "$unavailable" ]] || echo "- Not in this build (no section): $unavailable."
  echo
  echo "## How to read it"
  echo
  echo "Each method's section opens with the method at its defaults beside what it is measured against (the AO is"
  echo "visibility: white is open): the geometry truth (rays against the scene's triangles: what a viewer sees) and the"
  echo "screen-space reference (REFERENCE, rays through the depth buffer, with the method's falloff and thickness as"
  echo "\`obscura_reference_settings_for\` maps them: FFAO's thickness and GTAO's bitmask thickness, infinitely thick for"
  echo "HBAO, SAO, LSAO and GTAO's horizon mode; the ceiling of what a screen-space method can compute). Each setting is"
  echo "then one \`obscura compare --truth both\` run, whose command is under its table; the picture is that run's"
  echo "\`--strip\` sheet: the method at each value, labelled \`setting=value\`. Settings that change the falloff (radius,"
  echo "decay rate, C, the falloff itself) are measured against one truth per value, which follow the values (\`truth:"
  echo "setting=value\`)."
  echo
  echo "In the tables, **gpu ms** is the SDK's total of its passes and **wall ms** the time around"
  echo "\`obscura_render\` + \`glFinish\`, medians of 5 warm frames; **wall vs default** divides by the default's"
  echo "wall time in the same run. **mean_abs** is the mean absolute error of the visibility against the"
  echo "geometry truth (first) or the screen-space reference over the geometry pixels of the visible image (sky"
  echo "left out; lower is better), **within_5pct** the fraction of pixels within 0.05 of it (higher is better),"
  echo "the FFAO paper's two metrics (docs/quality.md), and **signed** the mean of method - truth: positive is"
  echo "too bright (missing occlusion), negative too dark."
  echo
  if [[ -n "$software" ]]; then
    echo "The times are Mesa llvmpipe's, a CPU rasteriser on a small machine: they say nothing about a GPU's"
    echo "milliseconds, and another process on the machine moves them. Only ratios within one table (one run)"
    echo "mean anything, and differences of a few per cent not even those. docs/performance.md has GPU numbers."
  else
    echo "The times are those of this machine's GPU (GL timer queries where it has them); compare ratios within"
    echo "one table, not across tables."
  fi
  echo
  echo "At $rays rays the screen-space reference has noise of its own (the reference section's \`rays\` table"
  echo "measures it), which puts a floor under its errors: differences of a few thousandths in mean_abs are noise."
  echo "The geometry truth at $truth_rays rays is within about 0.002 of its converged mean (tests/gl/geometry_truth_test.cpp)."
  echo
  echo "Methods: $(for m in "${methods[@]}"; do printf '[%s](#%s)\n' "$m" "$m"; done | paste -sd' ' -)."
  # The defaults' history (how `obscura tune` moved them, with each old and new default's error) is written by
  # hand between these markers and kept from the previous guide: it records runs this script does not make.
  if [[ -f "$doc" ]] && grep -q '^<!-- tuned defaults: begin' "$doc"; then
    echo
    sed -n '/^<!-- tuned defaults: begin/,/^<!-- tuned defaults: end/p' "$doc"
  fi
  cat "$body"
} >"$work/parameters.md"

mkdir -p "$image_dir"
find "$image_dir" -maxdepth 1 -name '*.png' -delete
cp "$work"/images/*.png "$image_dir/"
cp "$work/parameters.md" "$doc"
echo "parameter-guide: wrote $doc and $(find "$image_dir" -name '*.png' | wc -l) images ($(du -sh "$image_dir" | cut -f1)) in $((elapsed / 60)) min $((elapsed % 60)) s" >&2
