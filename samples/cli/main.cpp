// obscura: command-line front end of the Obscura SDK on the samples' scenes or a captured depth
// buffer, without a window (HeadlessGL).
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "cli_errors.h"
#include "commands.h"
#include "headless_gl.h"

namespace {

const char* const kUsage = R"(usage:
  obscura render [--method SPEC] [--set KEY=VALUE]... --out AO.png [--pfm AO.pfm] [--json OUT.json]
                 [--debug-view none|depth|normals|ao-before-blur|tap-count] [--sync-timing] [--gpu-code-paths]
                 [SCENE]
  obscura compare [--methods SPEC,SPEC,...] [--set KEY=VALUE]... [--truth geometry|screen|both]
                  [--truth-rays 1024] [--truth-seed 1] [--reference-rays 256] [--metrics-pixels geometry|all]
                  [--out-dir compare-output] [--json REPORT.json] [--strip STRIP.png]
                  [[--orbit DEG] --frames N] [--temporal on|off] [--motion-vectors on|off]
                  [--converged N|off] [--classes [RADIUS_M[,THICKNESS_M]]]
                  [--sync-timing] [--gpu-code-paths] [SCENE]
  obscura truth --out TRUTH.pfm [--depth-out DEPTH.pfm] [--png TRUTH.png] [--falloff SPEC]
                [--rays 1024] [--seed 1] [SCENE without --depth]
  obscura bench [--methods SPEC,SPEC,...] [--set KEY=VALUE]... [--sizes 1280x720,1920x1080,...]
                [--frames 50] [--warmup 5] [--clock auto|gpu-timer|wall] [--motion DEG] [--json BENCH.json]
                [--csv BENCH.csv] [SCENE without --size]
  obscura tune --method SPEC --scenes NAME[@VIEWPOINT],... [--size 320x180] [--budget RATIOx:SPEC]
               [--keys KEY,KEY,...] [--evaluations 60] [--truth-rays 256] [--seed 1] [--json TUNE.json]
               [--sync-timing] [SCENE options but --scene, --viewpoint, --eye/--target and --depth]
  obscura tune --method SPEC --captures DEPTH.pfm,... --truths TRUTH.pfm,... [--depth-kind, --near, --far,
               --reversed-z, --fovy, --guard-band as for --depth] [--budget, --keys, ... as above]
  obscura demo [--out-dir demo-output] [other compare options]
  obscura diff IMAGE.png|pfm REFERENCE.png|pfm [--tolerance mean=0.005,pixels=0.005,threshold=4]
               [--out DIFF.png] [--json REPORT.json]
  obscura --list-scenes | --list-methods | --list-settings [METHOD] | --help

SCENE (render, compare, bench, truth; tune takes the scenes as --scenes):
  --scene NAME|FILE.obj   atrium (default), terrain, objects, clutter, analytic, room, sliding (animated),
                          bunny, or an OBJ file
  --viewpoint NAME        one of the scene's cameras (--list-scenes; default: default)
  --eye X,Y,Z --target X,Y,Z [--fovy DEG]   a camera of your own instead
  --size WxH              the visible image (default 640x360); the depth texture adds the guard band
  --guard-band F          fraction of the size added on each side, in [0, 1) (default 0.1)
  --projection perspective|reversed|infinite|reversed-infinite|ortho    --depth-format d32f|d24|d24s8
  --msaa N    --no-clip-control    --normals (pass the scene's normals; else the SDK reconstructs them)
 or a captured depth buffer, a 1-channel PFM (rows bottom-up) whose size is the depth texture's:
  --depth FILE.pfm [--depth-kind linear|hardware] [--near 0.1] [--far 1000|inf] [--reversed-z]
                   [--fovy 60 (of the visible image)] [--guard-band 0 (fraction per side in the file)]

METHOD SPECS: NAME[:KEY=VALUE[:KEY=VALUE...]], e.g. hbao, hbao:directions=16:steps=48, reference:rays=512;
lists separate specs with ',' (--methods hbao,hbao:blur=off). Keys, defaults and ranges come from the
SDK's metadata (--list-settings); a spec starts from the method's defaults, derived settings (decay rates,
LSAO's K from its preset ...) follow the keys given unless given themselves (0: derive). Toggles take
on/off, enums their names or numbers (ffao:falloff=exponential, lsao:preset=k32), the falloff table 16
values V0/V1/.../V15 or @FILE (numbers separated by spaces, commas or newlines), needed with falloff=table.
--set KEY=VALUE applies to every method that has KEY (a key in a spec wins). A method the library does not
implement is an error (exit 1).
Defaults: render --method hbao; compare every available method but the reference; bench hbao.

render writes the AO (visibility) of the visible image. --json: scene, size, method, effective settings,
  gpu_ms (the SDK's total and per pass) and wall_ms, medians of warm frames.
Image files are named by their format, as diff reads them back: PFM files (render --pfm, truth --out and
  --depth-out) .pfm, PNG files (render --out, truth --png, compare --strip, diff --out) anything else.
compare renders each method and measures it against its truth with the same falloff as that method
  (obscura_reference_settings_for): --truth geometry (default for scenes) ray-traces the scene's
  triangles (--truth-rays per pixel, Embree on every core), screen (the only one for --depth files) is the
  SDK's screen-space REFERENCE through the depth buffer, infinitely thick unless reference:thickness is set
  (--reference-rays per pixel, from ray 2^23 of each pixel's sequence: not the rays of a compared reference
  method, which start at 0), both reports each (--truth-rays and --truth-seed need the geometry truth,
  --reference-rays the screen-space one). Progress on stderr. Prints per truth and method: gpu and wall ms,
  mean_abs, within_5pct (fraction of pixels within 0.05), PSNR, max_abs and the signed mean
  (method - truth: > 0 too bright), over the geometry pixels (sky left out and its fraction printed;
  --metrics-pixels all counts every pixel). --out-dir gets <n>_<method>.png,
  <n>_<method>_error_<geometry|screen>.png (white 0, black >= 0.2), <n>_<method>_signed_<truth>.png (red
  too dark, blue too bright, full at 0.2), geometry_truth_<k>.png and/or reference_<k>.png (one per
  falloff) and contact_sheet.png (method | truth | signed error). --frames N: N frames (images of the first), a
  still camera, or along an orbit of DEG degrees in total with --orbit DEG; an animated scene (sliding) moves
  through them. Errors are averaged over the frames, flicker measures the temporal error and last is the last
  frame's mean_abs. The frames pass their cameras and frame index to the SDK, and their motion vectors with
  --motion-vectors on (the default on an animated scene); --temporal on|off sets every method's temporal
  accumulation (the setting temporal.enabled, also a spec key: hbao,hbao:temporal.enabled=on), which then runs
  through the frames in order. --converged N (default 16 on an animated scene, else off) also renders each
  frame's many-sample image (N still frames accumulated): noise flicker is the flicker against those (the
  sampling noise's, apart from what the view itself changes) and converged their mean_abs; on an animated
  scene seen still a ghosting table follows: the error above the converged one of the pixels the moving object
  uncovered and of those whose converged AO it changed by > 0.02, by the frames since; with --orbit, of the
  pixels whose surface came into view (off the previous frame or hidden there), by the frames since. --motion-vectors and
  --converged need --frames; motion vectors need a single-sample depth buffer (no --msaa).
  --strip writes one sheet of the methods' AO labelled with their settings, then the first truth's
  images if there are several (falloffs differ).
  --classes [RADIUS_M[,THICKNESS_M]] (default 1,0.3) splits the geometry pixels by where a screen-space method's
  thickness assumption matters and prints per truth and method mean_abs and signed over each class: silhouette
  (a 4-neighbour, or sky, farther by more than max(0.1 m, 5 % of the depth)), halo (not silhouette, and a silhouette
  nearer by more than THICKNESS_M within RADIUS_M on screen at the pixel's depth, window capped at 256 px) and
  rest. View depth: the scene's primary rays, or a --depth file's depth; perspective projections only. Adds
  classes.png (sky black, rest white, halo blue, silhouette red) and "classes" to the --json report.
truth ray-traces the geometry truth of one view (--falloff: a method spec whose falloff it weighs hits
  with, default the reference's rho0 r=1 m) and writes it as PFM (and PNG); --depth-out writes the view's
  linear depth (positive view depth in metres, whole buffer with guard band, sky +inf) as --depth reads it,
  so the pair is a capture: render --depth DEPTH.pfm --guard-band G --fovy F --pfm AO.pfm, then
  diff AO.pfm TRUTH.pfm.
bench times warm frames, median and min, in total and per pass. Clock: GL timer queries on a GPU
  ("gpu-timer"), wall time around render + glFinish on llvmpipe/softpipe, whose timer queries read 0
  ("wall"; passes then by glFinish + CPU clock: the total includes a glFinish after every pass, which on a GPU
  reads above the unsynchronised frame). A configuration the SDK refuses, or a size whose depth cannot be
  rasterised, is reported (JSON "error", CSV pass "failed") and the others still run; the exit status is then 1.
  A size whose depth texture (guard band included) exceeds GL_MAX_TEXTURE_SIZE is refused before any runs (2).
  --motion DEG: the frames alternate between the view's camera and one turned DEG degrees back along the orbit,
  each reprojecting the other's history, so temporal accumulation times its moving path instead of a still camera's.
tune searches SPEC's settings, starting from them, for the lowest mean_abs against the geometry truth
  averaged over the --scenes views (e.g. atrium,objects,clutter@VIEWPOINT; default viewpoints otherwise), the
  truth weighed with each candidate's own falloff (obscura_reference_settings_for; one truth traced per
  falloff, --truth-rays per pixel, --seed). Searched: every number, enum and toggle of the method's metadata
  (--list-settings) that is not derived, not scheduling or noise (frame_index, first_ray, rays_per_dispatch),
  not temporal accumulation (temporal.*, FFAO's frame_split: tune weighs one frame) and does not define the
  falloff (radius, falloff_c, falloff, GTAO's falloff_range: they move the target); --keys names the settings to
  search instead (derived and falloff ones too; it refuses the scheduling, noise, temporal.* and frame_split ones).
  Ranges are the metadata's, on a log scale where they span more than 2 decades. The search (seeded,
  deterministic): compass steps with halving, pattern moves, random directions and restarts, --evaluations
  renders in all. Cost: the SDK's total summed over the scenes, median of warm frames, timed in the same run;
  --budget 1.0x:hbao rejects candidates costing more than 1.0 times the spec hbao on the same scenes, and the best
  is timed again against it (alternately) before it is reported; a candidate that is the budget's own
  configuration (resolved) costs exactly 1.0x, untimed, and the result is never farther from the truth than the
  start when the start is within the budget (it is timed again and kept). Settings of the best that leave its
  pictures unchanged are put back. SPEC may not turn temporal.enabled on (one frame per scene).
  Progress on stderr; prints the start's and the best's error (per scene) and cost, the budget, and the best
  settings as a spec (for --method) and as C code; --json writes them with every evaluation. Exit 1 when no
  candidate is within the budget. On a studio's own captures instead of scenes: --captures names depth files
  (read as render --depth reads them, with one set of depth options) and --truths the geometry truth of each
  one's visible image, traced with SPEC's falloff (obscura truth --falloff SPEC --out TRUTH.pfm --depth-out
  DEPTH.pfm); the error counts the depth's non-sky pixels, and keys that change the falloff are refused.
demo runs compare on the atrium at 640x360 with every available method against the geometry truth
  into demo-output/.
--sync-timing times passes with glFinish (automatic on llvmpipe/softpipe, whose timer queries read 0).
--gpu-code-paths (render, compare) runs the shader variants written for GPUs on a CPU rasteriser as well (the
  SDK's OBSCURA_CONTEXT_FLAG_GPU_CODE_PATHS, with its per-pass GL error checks): to see what a GPU renders on a
  machine without one; compare its images with `obscura diff`.
diff compares luminance in [0, 1] without GL: it passes when the mean absolute error is <= mean and
at most a fraction `pixels` of the pixels is off by more than threshold/255; exit 0 pass, 1 fail, 2 bad
input. --out writes an error heat map (white 0, black >= 0.2).
Options take a value as --name VALUE, or as --name=VALUE (a value that starts with "--" only so). Output files
  are checked before the work: one that cannot be written, or two outputs naming one file, is a bad argument.
Exit status: 0 success, 1 an API, GL or file failure, 2 bad arguments (a size or --msaa past the GL context's
  limits included).
Environment: OBSCURA_GL_BACKEND=auto|egl-device|egl-surfaceless|osmesa picks the headless GL backend.
)";

}  // namespace

int main(int argc, char** argv) {
    using namespace obscura::cli;
    std::vector<std::string> arguments(argv + 1, argv + argc);
    if (arguments.empty() || arguments[0] == "--help" || arguments[0] == "-h" || arguments[0] == "help") {
        std::fputs(kUsage, arguments.empty() ? stderr : stdout);
        return arguments.empty() ? 2 : 0;
    }
    const std::string command = arguments[0];
    ArgumentList rest(std::vector<std::string>(arguments.begin() + 1, arguments.end()));
    try {
        if (command == "--list-scenes" || command == "list-scenes") return run_list_scenes(rest);
        if (command == "--list-methods" || command == "list-methods") return run_list_methods(rest);
        if (command == "--list-settings" || command == "list-settings") return run_list_settings(rest);
        if (command == "render") return run_render(rest);
        if (command == "compare") return run_compare(rest);
        if (command == "bench") return run_bench(rest);
        if (command == "demo") return run_demo(rest);
        if (command == "diff") return run_diff(rest);
        if (command == "truth") return run_truth(rest);
        if (command == "tune") return run_tune(rest);
        throw UsageError("unknown command '" + command + "'");
    } catch (const UsageError& error) {
        std::fprintf(stderr, "obscura: %s (see 'obscura --help')\n", error.what());
        return 2;
    } catch (const ApiError& error) {
        std::fprintf(stderr, "obscura: error: %s\n", error.what());
        return 1;
    } catch (const obscura::samples::HeadlessGLError& error) {
        std::fprintf(stderr, "obscura: no OpenGL: %s\n", error.what());
        return 1;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "obscura: error: %s\n", error.what());
        return 1;
    }
}
