#include "app/cli.h"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <memory>

#include "core/error.h"
#include "core/memory.h"
#include "export/image_render.h"
#include "run/report.h"
#include "scene/stage.h"

namespace rad {

void parse_shard(const std::string& text, int* index, int* count) {
  std::string spec = text;
  if (text == "slurm") {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* n = std::getenv("SLURM_ARRAY_TASK_COUNT");
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    if (!id || !n)
      throw Error("'slurm' needs SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT (sbatch --array)");
    long i = std::strtol(id, nullptr, 10) - (min ? std::strtol(min, nullptr, 10) : 0);
    spec = std::to_string(i) + "/" + n;
  }
  long i = -1, n = 0;
  char slash = 0, end = 0;
  if (std::sscanf(spec.c_str(), "%ld%c%ld%c", &i, &slash, &n, &end) != 3 || slash != '/' || n < 1 ||
      n > 1000000 || i < 0 || i >= n) {
    throw Error("expected I/N with 0 <= I < N, or 'slurm'; got '" + spec + "'");
  }
  *index = int(i);
  *count = int(n);
}

namespace {

// Checks of an option's text that say what was expected ("--roulette: expects a number, 0 or
// more, got 'five'"), in place of CLI11's, which print the range's bounds in full.
CLI::Validator non_negative() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        double v = 0;
        char end = 0;
        if (std::sscanf(text.c_str(), "%lf%c", &v, &end) == 1 && std::isfinite(v) && v >= 0) {
          return {};
        }
        return fmt::format("expects a number, 0 or more, got '{}'", text);
      },
      "");
}
CLI::Validator whole_number(long lo, long hi) {
  return CLI::Validator(
      [lo, hi](const std::string& text) -> std::string {
        long v = 0;
        char end = 0;
        if (std::sscanf(text.c_str(), "%ld%c", &v, &end) == 1 && v >= lo && v <= hi) return {};
        return fmt::format("expects a whole number from {} to {}, got '{}'", lo, hi, text);
      },
      "");
}

const std::string kStageHelp = fmt::format(
    "For a model: set it on a grey floor (reflectance {}) under a soft area light scaled to its "
    "box, giving {:g} lux on the floor below it, and frame it (unless --camera); the model's own "
    "lights stay",
    kStageFloorReflectance, kStageIlluminance);
const std::string kSunHelp = fmt::format(
    "For a model: --stage outdoors: a sun of {:g} lux at ELEVATION,AZIMUTH degrees (azimuth from "
    "the front, +z, toward +x; default {:g},{:g}), the area light then a sky of {:g} lux; give it "
    "after the scene and output when it takes no angles",
    kStageSunIlluminance, SunAngles{}.elevation_deg, SunAngles{}.azimuth_deg, kStageSkyIlluminance);

// Options added while it lives are listed under `name` in the help and in the man page; the
// others under "Options".
class OptionGroup {
 public:
  OptionGroup(CLI::App& app, const char* name) : app_(app) { app_.option_defaults()->group(name); }
  ~OptionGroup() { app_.option_defaults()->group("Options"); }
  OptionGroup(const OptionGroup&) = delete;
  OptionGroup& operator=(const OptionGroup&) = delete;

 private:
  CLI::App& app_;
};

// An option given once per value (--emit 'A=1' --emit 'B=2', --image a.png --image b.hdr), all
// kept in order: one value each, or a vector option would swallow the positionals after it
// (`--image out.png scene.des out.ply`).
void repeatable(CLI::Option* o) {
  o->expected(1)->allow_extra_args(false)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

// --emit, --light-group, --stage, --sun and --hierarchy: how a scene file is read, for every mode.
struct SceneReading {
  std::vector<std::string> emit;
  std::vector<std::string> light_groups;
  std::vector<std::string> two_sided;
  std::string hierarchy;
  bool stage = false;
  std::string sun;
  CLI::Option* sun_option = nullptr;

  void add_to(CLI::App& app, const char* emit_help, const char* hierarchy_help) {
    const OptionGroup group(app, "Scene");
    repeatable(app.add_option("--emit", emit, emit_help));
    repeatable(app.add_option(
        "--light-group", light_groups,
        "For a model: its materials and lights whose name matches the pattern are in "
        "light group NAME, e.g. --light-group 'Lamp*=kitchen' (repeatable; a "
        "description says 'Group \"NAME\"'). Each group's light is solved and written "
        "on its own, to be mixed after the solve; the last match wins"));
    repeatable(app.add_option(
        "--two-sided", two_sided,
        "For a model: its materials, and its groups (OBJ o and g, glTF nodes), whose "
        "name matches the pattern are two-sided, lit and shooting on both faces, "
        "e.g. --two-sided 'Leaf*' (repeatable; glTF says doubleSided, a description "
        "'TwoSided Yes')"));
    app.add_flag("--stage", stage, kStageHelp);
    // The angles are optional: --sun alone is the default sun.
    sun_option = app.add_option("--sun", sun, kSunHelp)->expected(0, 1);
    app.add_option("--hierarchy", hierarchy, hierarchy_help);
  }
  // After parsing; throws CLI::ValidationError naming the option.
  void apply(SceneInput& in) const {
    try {
      for (const std::string& e : emit) in.model.emit.push_back(parse_emit_rule(e));
    } catch (const Error& e) {
      throw CLI::ValidationError("--emit", e.message());
    }
    try {
      for (const std::string& g : light_groups)
        in.model.light_groups.push_back(parse_group_rule(g));
    } catch (const Error& e) {
      throw CLI::ValidationError("--light-group", e.message());
    }
    in.model.two_sided = two_sided;
    if (stage || sun_option->count() > 0) {
      StageOptions o;
      try {
        if (sun_option->count() > 0) o.sun = parse_sun_angles(sun);
      } catch (const Error& e) {
        throw CLI::ValidationError("--sun", e.message());
      }
      in.model.stage = o;
    }
    try {
      if (!hierarchy.empty()) in.hierarchy = parse_hierarchy_mode(hierarchy);
    } catch (const Error& e) {
      throw CLI::ValidationError("--hierarchy", e.message());
    }
  }
};

// The solve: RunOptions, for every mode that solves. `time_limit`: whether the mode has an end
// for it to cut short (rad serve solves until stopped).
// Every default comes from the struct that owns it (RunOptions, SolverOptions).
struct Solving {
  std::string backend = to_string(RunOptions{}.backend);
  std::string method = to_string(SolverOptions{}.method);
  int samples = SolverOptions{}.sample_grid * SolverOptions{}.sample_grid;
  int max_samples = SolverOptions{}.max_sample_grid * SolverOptions{}.max_sample_grid;
  size_t kept_rays_mib = SolverOptions{}.kept_rays_bytes >> 20;

  void add_to(CLI::App& app, RunOptions& r, bool time_limit) {
    const OptionGroup group(app, "Solving");
    app.add_option("--backend", backend, "Shadow-ray backend: embree, grid or brute")
        ->capture_default_str();
    app.add_flag("!--no-packets", r.packets, "Trace shadow rays one at a time (Embree)");
    app.add_option("--threads", r.threads, "Worker threads, 0 for all cores")
        ->capture_default_str();
    SolverOptions& o = r.solver;
    app.add_flag("!--no-shadows", o.shadows, "No shadow rays: every visibility term is 1");
    app.add_option("--min-size", o.min_size,
                   fmt::format("Smallest element size (the legs of a right triangle of its "
                               "area), scene units (default: scene size / {}, the diameter of a "
                               "sphere holding it)",
                               SolverOptions::kMinSizeDivisor));
    app.add_option("--max-size", o.max_size,
                   fmt::format("Largest element edge of the initial mesh, scene units (default: "
                               "scene size / {}, at least 2 x --min-size)",
                               SolverOptions::kMaxSizeDivisor));
    app.add_option("--samples", samples,
                   "Fewest samples per shooting cluster (a square: 1, 4, 9, 16, ... up to 256)")
        ->capture_default_str();
    app.add_option("--max-samples", max_samples,
                   "Most samples per shooting cluster (a square, up to 256): a big source gets "
                   "more than --samples, as many as bring their spacing within the initial mesh's "
                   "element size (--max-size) or this many; give both to fix the count")
        ->capture_default_str();
    app.add_option("--form-factor", method,
                   "analytic (the exact unoccluded form factor times the visibility the samples "
                   "see) or samples (each sample a small disc, their form factors summed)")
        ->capture_default_str();
    app.add_option("--threshold", o.subdivision_threshold,
                   "Subdivision limit: split where vertices differ by more than this fraction of "
                   "the scene's radiosity scale (emitted power / total area)")
        ->capture_default_str();
    app.add_option("--intensity-cut", o.intensity_cut,
                   "One shadow ray instead of one per sample when a vertex's unoccluded gain is "
                   "below this fraction of the radiosity scale")
        ->capture_default_str();
    app.add_option("--roulette", o.roulette,
                   "Russian roulette: a vertex whose gain from a shot is bounded below this "
                   "fraction of the radiosity scale gathers with probability bound / level, its "
                   "gain divided by it (unbiased; far receivers cost less); 0: off")
        ->capture_default_str()
        ->check(non_negative());
    app.add_option("--penumbra-rays", o.penumbra_rays,
                   "Where a vertex's shadow rays to a lamp's major shot disagree (a penumbra), or "
                   "its rays to the lamp's corners do, this many more per sample, to points of "
                   "its stratum that differ from vertex to vertex, and their mean; where all "
                   "find the lamp hidden, two of them probe for it through gaps; 0: off (a "
                   "penumbra in steps of a sample)")
        ->capture_default_str()
        ->check(whole_number(0, 64));
    app.add_option("--converge", o.converge,
                   "Stop when unshot energy <= this fraction of the emitted energy")
        ->capture_default_str();
    app.add_option("--max-shots", o.max_shots,
                   "Stop after this many shots (0 writes the unlit scene: emission only)");
    if (time_limit) app.add_option("--time-limit", o.time_limit, "Stop after this many seconds");
    app.add_option(
           "--kept-rays", kept_rays_mib,
           "MiB for shadow-ray answers kept between shots of the same cluster, which "
           "casts the same rays again, at most 1/8 of --max-memory; 0 traces every ray every "
           "time, with the same result")
        ->capture_default_str();
    app.add_flag("!--no-culling", o.occlusion_culling,
                 "No occlusion culling (on by default: receivers that a flat occluder, a wall, "
                 "hides from a source get no shadow rays)");
    app.add_flag("!--no-overshoot", o.overshoot,
                 "No overshooting (Feda & Purgathofer 1992, on by default: shooters also shoot "
                 "their share of the ambient term, which converges in fewer shots)");
  }
  void apply(RunOptions& r) const {
    try {
      r.backend = parse_backend_kind(backend);
    } catch (const Error& e) {
      throw CLI::ValidationError("--backend", e.message());
    }
    if (method == "analytic") {
      r.solver.method = FormFactorMethod::Analytic;
    } else if (method == "samples") {
      r.solver.method = FormFactorMethod::Samples;
    } else {
      throw CLI::ValidationError("--form-factor", "expected analytic or samples, got " + method);
    }
    const auto grid = [](int n, const char* option) {
      const int m = int(std::lround(std::sqrt(double(n))));
      if (n < 1 || n > 256 || m * m != n) {
        throw CLI::ValidationError(option,
                                   "must be a square number from 1 to 256 (1, 4, 9, 16, ...)");
      }
      return m;
    };
    r.solver.kept_rays_bytes = kept_rays_mib << 20;
    r.solver.sample_grid = grid(samples, "--samples");
    r.solver.max_sample_grid = std::max(grid(max_samples, "--max-samples"), r.solver.sample_grid);
  }
};

// How the solution is shown and rendered: OutputOptions but the file names, for every mode that
// writes a solution. `images`: whether the mode takes --image (rad batch names its by --formats).
struct Showing {
  // Every default comes from the struct that owns it (OutputOptions, Camera).
  std::string tonemap = to_string(OutputOptions{}.tonemap), camera, false_colour,
              render = OutputOptions{}.render == ImageRender::Final ? "final" : "preview",
              background = "0,0,0";
  double false_colour_max = 0.0;
  int false_colour_log = 0;
  CLI::Option *max_option = nullptr, *log_option = nullptr;
  std::string size =
      fmt::format("{}x{}", OutputOptions{}.image_width, OutputOptions{}.image_height);

  void add_to(CLI::App& app, OutputOptions& o, bool images, bool final_render) {
    const OptionGroup group(app, "Images and display");
    app.add_flag("--ascii", o.ascii, "Write text PLY instead of binary");
    app.add_flag("!--no-ambient", o.ambient,
                 "Display colours without Cohen's ambient term (the stored radiosity never has "
                 "it)");
    app.add_option("--tonemap", tonemap, "Display tone curve: clamp, reinhard or aces")
        ->capture_default_str();
    app.add_option("--exposure", o.exposure, "Stops added to the automatic exposure")
        ->capture_default_str();
    if (images) {
      repeatable(app.add_option("--image", o.images,
                                "Render the solved scene to this image: .png (tone-mapped sRGB) or "
                                "linear .hdr, .exr, .pfm (repeatable)"));
    }
    app.add_option(
        "--camera", camera,
        fmt::format("Image camera: eye, target and vertical field of view in degrees, y up "
                    "(default: the scene framed from outside its most open side, fov {}; when "
                    "every side is closed (a room), from high in the corner with the least in the "
                    "way, looking down across it, {} degrees either side); the camera used is "
                    "printed in this syntax",
                    kDefaultFovDeg, kRoomHalfWidthDeg));
    app.add_option("--size", size, "Image size WxH in pixels")->capture_default_str();
    if (final_render) {
      app.add_option("--render", render,
                     "How images are made: final (each pixel gathers its direct light afresh "
                     "and reads the bounced light from the solution: sharp shadows and "
                     "textures) or preview (the solved mesh's colours, interpolated: fast); false "
                     "colour images are always of the mesh")
          ->capture_default_str();
      app.add_option("--pixel-samples", o.pixel_samples,
                     "Final render: samples per pixel along each side (3: 9 per pixel)")
          ->check(whole_number(1, 16))
          ->capture_default_str();
      app.add_option("--background", background,
                     "Final render: what pixels show where nothing is seen: a linear colour R,G,B "
                     "(radiosity units, as the scene's), or 'transparent' (an alpha channel in "
                     ".png and .exr)")
          ->capture_default_str();
      app.add_flag("--group-images", o.group_images,
                   "With two light groups or more: beside each image, one per group of its light "
                   "alone (box.png: box.GROUP.png), same camera and exposure");
    }
    app.add_option("--false-colour", false_colour,
                   "lux: images show the illuminance (the luminance of the light arriving) in "
                   "false colour, dark blue to red, with a legend on their left (after "
                   "Radiance's falsecolor)");
    max_option =
        app.add_option("--false-colour-max", false_colour_max,
                       "Top of the false colour scale, lux (default: a round number above 99% of "
                       "the vertices' illuminance)");
    log_option =
        app.add_option("--false-colour-log", false_colour_log,
                       fmt::format("A logarithmic false colour scale over this many decades below "
                                   "its top (1 to {}; default linear from 0)",
                                   kMaxFalseColourDecades));
  }
  void apply(OutputOptions& o) const {
    try {
      o.tonemap = parse_tone_curve(tonemap);
    } catch (const Error& e) {
      throw CLI::ValidationError("--tonemap", e.message());
    }
    try {
      if (!camera.empty()) o.camera = parse_camera(camera);
    } catch (const Error& e) {
      throw CLI::ValidationError("--camera", e.message());
    }
    apply_false_colour(o);
    if (render != "final" && render != "preview") {
      throw CLI::ValidationError("--render",
                                 fmt::format("expected final or preview, got {}", render));
    }
    o.render = render == "final" ? ImageRender::Final : ImageRender::Preview;
    o.transparent = background == "transparent";
    if (!o.transparent) {
      float r = 0, g = 0, b = 0;
      char end = 0;
      if (std::sscanf(background.c_str(), "%f,%f,%f%c", &r, &g, &b, &end) != 3 ||
          !std::isfinite(r) || !std::isfinite(g) || !std::isfinite(b) || r < 0 || g < 0 || b < 0) {
        throw CLI::ValidationError(
            "--background",
            fmt::format("expected R,G,B (three numbers >= 0) or transparent, got {}", background));
      }
      o.background = Vec3(r, g, b);
    }
    char x = 0, end = 0;
    if (std::sscanf(size.c_str(), "%d%c%d%c", &o.image_width, &x, &o.image_height, &end) != 3 ||
        x != 'x' || o.image_width < 1 || o.image_height < 1 || o.image_width > kMaxImageSize ||
        o.image_height > kMaxImageSize) {
      throw CLI::ValidationError(
          "--size", fmt::format("expected WxH in pixels (1 to {}), got {}", kMaxImageSize, size));
    }
  }
  // --false-colour and its scale; the scale's options alone would change nothing.
  void apply_false_colour(OutputOptions& o) const {
    if (false_colour.empty()) {
      for (const CLI::Option* given : {max_option, log_option}) {
        if (given->count() > 0) {
          throw CLI::ValidationError(given->get_name(),
                                     "sets the false colour scale: add --false-colour lux");
        }
      }
      return;
    }
    if (false_colour != "lux") {
      throw CLI::ValidationError("--false-colour",
                                 "expected lux (the illuminance), got '" + false_colour + "'");
    }
    if (max_option->count() > 0 && !(false_colour_max > 0.0 && std::isfinite(false_colour_max))) {
      throw CLI::ValidationError(
          "--false-colour-max",
          fmt::format("expected a positive number of lux, got {}", false_colour_max));
    }
    if (log_option->count() > 0 &&
        (false_colour_log < 1 || false_colour_log > kMaxFalseColourDecades)) {
      throw CLI::ValidationError("--false-colour-log",
                                 fmt::format("expected 1 to {} decades, got {}",
                                             kMaxFalseColourDecades, false_colour_log));
    }
    o.false_colour = true;
    o.false_colour_scale = {.max = false_colour_max, .log_decades = false_colour_log};
  }
};

void add_max_memory(CLI::App& app, std::string& text) {
  const OptionGroup group(app, "Solving");
  app.add_option("--max-memory", text,
                 "Memory the solve may use (512M, 8G, ...; default 90% of the machine's, or of the "
                 "control group's): a scene "
                 "that could need more is refused; a solve that reaches it stops and writes");
}

void apply_max_memory(const std::string& text, size_t& bytes) {
  try {
    if (!text.empty()) bytes = parse_byte_size(text);
  } catch (const Error& e) {
    throw CLI::ValidationError("--max-memory", e.message());
  }
}

const char* const kOverview =
    "rad: diffuse interreflection (radiosity) by progressive shooting with ray-traced\n"
    "vertex-to-source form factors and adaptive subdivision.\n\n"
    "  rad [options] SCENE OUTPUT              solve and write every vertex's colour\n"
    "  rad --check SCENE                       parse, validate and summarise only\n"
    "  rad --cross-check BACKEND SCENE         solve with --backend and BACKEND; report\n"
    "                                          every disagreement (rays and radiosity)\n"
    "  rad batch OUTDIR SCENE... [options]     solve many scenes; rad batch --help\n"
    "  rad serve SCENE [options]               solve in the background and watch, edit and\n"
    "                                          export it in a browser; rad serve --help\n"
    "  rad convert IN OUT                      the scene itself in another format;\n"
    "                                          rad convert --help\n\n"
    "SCENE is a description (.des) or a model (.obj, .ply, .gltf, .glb; name its lamps with\n"
    "--emit, or light it with --stage). OUTPUT is a mesh: .ply, .off, .obj, .gltf or .glb.\n\n"
    "Examples:\n"
    "  rad scenes/cornell_box.des box.ply --image box.png --stats-json box.json\n"
    "  rad model.glb model.ply --stage --image model.png\n";

const char* const kBatchHelp =
    "rad batch: many scenes solved with the same options. Each scene's outputs are named\n"
    "after it in OUTDIR, one per --formats extension, with its statistics (NAME.json) and a\n"
    "row in OUTDIR/batch.json. A scene whose outputs are complete from an earlier run with\n"
    "the same options is skipped, so a stopped batch started again carries on.\n\n"
    "Examples:\n"
    "  rad batch out scenes/*.des --formats ply,png --max-shots 500\n"
    "  rad batch out list.txt --shard 0/4       the first of four processes sharing list.txt\n";

const char* const kServeHelp =
    "rad serve: a scene solved in the background and shown in a browser, where its objects'\n"
    "colours and lights can be changed while it solves. Ctrl-C (or SIGTERM) stops it and\n"
    "writes --output and --image from what the page showed last.\n\n"
    "Example:\n"
    "  rad serve scenes/cornell_box.des --port 8080 --output box.ply\n"
    "  then open http://127.0.0.1:8080/\n";

const char* const kConvertHelp =
    "rad convert: a scene (description, OBJ, glTF or PLY) written in another of those\n"
    "formats: geometry, materials and as much of the hierarchy as the target holds.\n"
    "Nothing is solved.\n\n"
    "Example:\n"
    "  rad convert room.obj room.des --emit 'Lamp*=12'\n";

// The same statuses for every mode (scripts tell a bad command line from a bad scene), each
// described as the mode meets it.
std::string exit_status_help(const std::string& mode) {
  std::string h =
      "\nExit status:\n"
      "  0    done\n"
      "  1    input error: a scene or file that cannot be read or written";
  h += mode == "rad batch" ? ", or any scene that failed\n"
       : mode == "rad"     ? ", or a scene with nothing to solve\n"
                           : "\n";
  h += "  2    usage error: an unknown option or a bad value on the command line\n";
  if (mode == "rad serve") {
    h += "  Ctrl-C (SIGINT) or SIGTERM ends it: the outputs are written, and the status is 0\n";
  } else if (mode != "rad convert") {
    h +=
        "  130  stopped by Ctrl-C (SIGINT), 143 by SIGTERM: the outputs hold the solution so far\n";
  }
  return h;
}

const char* const kEmitHelp =
    "For a model scene (.obj, .ply, .gltf, .glb): materials matching the pattern emit VALUE "
    "times their colour, e.g. --emit 'Lamp*=12' (repeatable; refused for a description, whose "
    "emission is written in it)";
const char* const kHierarchyHelp =
    "How objects are grouped for shadow rays: file (as written), auto (Pures regrouped into "
    "compact Composites and Assemblies of what is near) or flat (one Composite); default auto "
    "for models, file for descriptions";

// What every solving mode registers: the solve, how the solution is shown, how the scene is
// read, --quiet, and (for a mode whose solve has an end) --max-memory.
struct SolvingMode {
  Solving solving;
  Showing showing;
  SceneReading reading;
  std::string max_memory;
  bool memory_limit = false;
  double unit = 1.0;
  CLI::Option* unit_option = nullptr;

  void add_to(CLI::App& app, CommandLine& c, bool time_limit, bool images, bool memory) {
    solving.add_to(app, c.run, time_limit);
    // A job (not rad serve, whose images are drawn from its live mesh) may render by final gather.
    showing.add_to(app, c.job.outputs, images, /*final_render=*/memory);
    reading.add_to(app, kEmitHelp, kHierarchyHelp);
    unit_option = app.add_option("--unit", unit,
                                 "Metres per scene unit of a description, OBJ or PLY scene (0.001: "
                                 "millimetres), for lights in candela and lux per square metre "
                                 "(glTF is in metres: ignored there); default 1")
                      ->group("Scene");
    memory_limit = memory;
    if (memory_limit) add_max_memory(app, max_memory);
    app.add_flag("-q,--quiet", c.run.quiet, "Print errors only (no stages, progress or warnings)");
  }
  void apply(CommandLine& c) const {
    solving.apply(c.run);
    showing.apply(c.job.outputs);
    reading.apply(c.job.input);
    if (unit_option->count() > 0) {
      if (!(unit > 0.0 && std::isfinite(unit))) {
        throw CLI::ValidationError(
            "--unit", fmt::format("expected the metres in one scene unit, a positive number (0.01 "
                                  "for centimetres), got {}",
                                  unit));
      }
      c.job.input.unit = unit;
    }
    if (memory_limit) apply_max_memory(max_memory, c.job.max_memory);
  }
};

// What an option's value is called in the help and the man page: what it looks like, or what it
// is (a number, a fraction of the radiosity scale, a file). Options not named here are called by
// their kind: N (a whole number), X (a number) or TEXT.
const std::map<std::string, std::string> kValueLabels = {
    {"--backend", "embree|grid|brute"},
    {"--cross-check", "BACKEND"},
    {"--form-factor", "analytic|samples"},
    {"--min-size", "SIZE"},
    {"--max-size", "SIZE"},
    {"--threshold", "FRACTION"},
    {"--intensity-cut", "FRACTION"},
    {"--roulette", "FRACTION"},
    {"--converge", "FRACTION"},
    {"--time-limit", "SECONDS"},
    {"--kept-rays", "MIB"},
    {"--tonemap", "clamp|reinhard|aces"},
    {"--exposure", "STOPS"},
    {"--image", "FILE"},
    {"--camera", "EX,EY,EZ,TX,TY,TZ[,FOV]"},
    {"--size", "WxH"},
    {"--render", "final|preview"},
    {"--background", "R,G,B|transparent"},
    {"--false-colour", "lux"},
    {"--false-colour-max", "LUX"},
    {"--false-colour-log", "DECADES"},
    {"--emit", "PATTERN=VALUE"},
    {"--light-group", "PATTERN=NAME"},
    {"--two-sided", "PATTERN"},
    {"--sun", "[ELEVATION,AZIMUTH]"},
    {"--hierarchy", "file|auto|flat"},
    {"--unit", "METRES"},
    {"--max-memory", "SIZE"},
    {"--stats-json", "FILE"},
    {"--checkpoint", "FILE"},
    {"--checkpoint-every", "SECONDS"},
    {"--formats", "EXT,..."},
    {"--shard", "I/N|slurm"},
    {"--port", "PORT"},
    {"--host", "ADDRESS"},
    {"--output", "FILE"},
};

// The kind of value CLI11 converts an option's text to: INT, UINT, FLOAT or TEXT (without the
// validators it appends: "FLOAT:NONNEGATIVE").
std::string value_kind(const CLI::Option& o) {
  const std::string t = o.get_type_name();
  return t.substr(0, t.find(':'));
}

// "-q,--quiet", "--no-packets": the names alone, without CLI11's "{false}" for a negated flag.
std::string option_names(const CLI::Option& o) {
  std::string names;
  for (const std::string& s : o.get_snames()) names += (names.empty() ? "-" : ",-") + s;
  for (const std::string& l : o.get_lnames()) names += (names.empty() ? "--" : ",--") + l;
  return names;
}

// What follows an option's name: its value's label, or nothing for a flag.
std::string value_label(const CLI::Option& o) {
  if (o.get_type_size() == 0) return {};
  if (!o.get_option_text().empty()) return o.get_option_text();
  const std::string kind = value_kind(o);
  return kind == "INT" || kind == "UINT" ? "N" : kind == "FLOAT" ? "X" : kind;
}

// The description, with the default CLI11 captured from the bound value.
std::string option_description(const CLI::Option& o) {
  std::string d = o.get_description();
  if (o.get_type_size() != 0 && !o.get_default_str().empty()) {
    d += " (default " + o.get_default_str() + ")";
  }
  return d;
}

// `text` broken into lines of at most `width` characters at spaces, each after `indent`
// spaces but the first (which continues whatever precedes it).
std::string wrap(const std::string& text, size_t indent, size_t width) {
  std::string out, line;
  size_t at = 0;
  while (at < text.size()) {
    const size_t space = std::min(text.find(' ', at), text.size());
    const std::string word = text.substr(at, space - at);
    if (!line.empty() && indent + line.size() + 1 + word.size() > width) {
      out += line + "\n" + std::string(indent, ' ');
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    at = space + 1;
  }
  return out + line;
}

// CLI11's help in rad's words: `--threads N`, the default at the end of the description, none
// of CLI11's notation (`FLOAT:NONNEGATIVE=0.01`, `INT:INT in [0 - 64]`, `{false}`), and the
// descriptions wrapped to a terminal's width.
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_name(const CLI::Option* o, bool positional) const override {
    return positional ? o->get_name(true, false) : option_names(*o);
  }
  std::string make_option_opts(const CLI::Option* o) const override {
    const std::string label = value_label(*o);
    return label.empty() ? "" : " " + label;
  }
  std::string make_option_desc(const CLI::Option* o) const override {
    return option_description(*o);
  }
  std::string make_option(const CLI::Option* o, bool positional) const override {
    constexpr size_t kColumn = 30, kWidth = 100;
    std::string name = "  " + make_option_name(o, positional);
    if (!positional) name += make_option_opts(o);
    name += name.size() + 1 < kColumn ? std::string(kColumn - name.size(), ' ')
                                      : "\n" + std::string(kColumn, ' ');
    return name + wrap(make_option_desc(o), kColumn, kWidth) + "\n";
  }
};

// One mode's command line: the options (bound to `line` and to what `keep` holds), and what
// is checked and filled in after parsing.
struct ModeParser {
  explicit ModeParser(const std::string& description, const std::string& name)
      : app(description, name) {
    app.formatter(std::make_shared<HelpFormatter>());
    app.footer(exit_status_help(name));
    app.set_version_flag("--version", std::string("rad ") + rad_version(),
                         "Print rad's version and exit");
  }
  // A value an option is bound to, alive as long as the parser.
  template <class T>
  T& keep() {
    auto held = std::make_shared<T>();
    kept.push_back(held);
    return *held;
  }
  std::vector<std::string> option_names() const {
    std::vector<std::string> names;
    for (const CLI::Option* o : app.get_options()) {
      for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
      for (const std::string& s : o->get_snames()) names.push_back("-" + s);
    }
    return names;
  }

  CLI::App app;
  CommandLine line;
  std::function<void(CommandLine&)> apply = [](CommandLine&) {};
  std::vector<std::shared_ptr<void>> kept;
};

// rad convert IN OUT: only how the scene is read (a solve's options would be silently
// meaningless here).
void define_convert(ModeParser& p) {
  CommandLine& c = p.line;
  c.mode = Mode::Convert;
  c.job.input.model.require_emission = false;
  CLI::App& app = p.app;
  app.add_option("IN", c.job.input.path, "Scene to read: .des, .obj, .gltf, .glb or .ply")
      ->required();
  app.add_option("OUT", c.converted, "Scene to write: .des, .obj (+ .mtl), .gltf, .glb or .ply")
      ->required();
  SceneReading& reading = p.keep<SceneReading>();
  reading.add_to(app,
                 "For a model: materials matching the pattern emit VALUE times their colour "
                 "(repeatable)",
                 "file (as read: a model's groups and materials), auto (the Pures regrouped "
                 "into compact Composites and Assemblies of what is near) or flat; default file");
  app.add_flag("-q,--quiet", c.run.quiet, "Print errors only");
  p.apply = [&reading](CommandLine& r) { reading.apply(r.job.input); };
}

// rad batch OUTDIR SCENE...: a solve's options for every scene; outputs named by --formats.
void define_batch(ModeParser& p) {
  CommandLine& c = p.line;
  c.mode = Mode::Batch;
  CLI::App& app = p.app;
  std::string& formats = p.keep<std::string>();
  std::string& shard = p.keep<std::string>();
  formats = "ply,png";
  app.add_option("OUTDIR", c.batch.dir, "Folder for every scene's outputs and statistics")
      ->required();
  app.add_option("SCENE", c.batch.scenes,
                 "Scene files, or .txt files listing them (one a line, '#' comments, paths "
                 "relative to the list)")
      ->required();
  app.add_option("--formats", formats,
                 "Outputs per scene, by extension: mesh (ply, off, obj, gltf, glb) and image "
                 "(png, hdr, exr, pfm)")
      ->capture_default_str();
  app.add_option("--shard", shard,
                 "Solve this process's share of the list: I/N takes scenes I, I + N, I + 2N, "
                 "... (0 <= I < N); 'slurm' takes I and N from the Slurm job array "
                 "(SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN, SLURM_ARRAY_TASK_COUNT)");
  SolvingMode& solving = p.keep<SolvingMode>();
  solving.add_to(app, c, /*time_limit=*/true, /*images=*/false, /*memory=*/true);
  p.apply = [&solving, &formats, &shard](CommandLine& r) {
    solving.apply(r);
    if (!shard.empty()) {
      try {
        parse_shard(shard, &r.batch.shard_index, &r.batch.shard_count);
      } catch (const Error& e) {
        throw CLI::ValidationError("--shard", e.message());
      }
    }
    r.batch.formats.clear();
    for (size_t at = 0; at <= formats.size();) {
      const size_t comma = std::min(formats.find(',', at), formats.size());
      if (comma > at) r.batch.formats.push_back(formats.substr(at, comma - at));
      at = comma + 1;
    }
  };
}

// rad serve SCENE: a solve without an end (no --time-limit), no checkpoints or statistics;
// the outputs are written when it stops.
void define_serve(ModeParser& p) {
  CommandLine& c = p.line;
  c.mode = Mode::Serve;
  CLI::App& app = p.app;
  app.add_option("SCENE", c.job.input.path,
                 "Scene: a description (.des) or a model (.obj, .ply, .gltf, .glb)")
      ->required();
  app.add_option("--port", c.server.port, "TCP port, 0 for any free port")
      ->check(whole_number(0, 65535))
      ->capture_default_str();
  app.add_option("--host", c.server.host,
                 "Address to listen on (other than loopback exposes the scene and its edits to "
                 "the network)")
      ->capture_default_str();
  app.add_option("--output", c.job.outputs.mesh,
                 "Mesh written when the server stops (.ply, .off, .obj, .gltf, .glb)");
  SolvingMode& solving = p.keep<SolvingMode>();
  solving.add_to(app, c, /*time_limit=*/false, /*images=*/true, /*memory=*/false);
  p.apply = [&solving](CommandLine& r) { solving.apply(r); };
}

// rad [options] SCENE OUTPUT, and its --check and --cross-check.
void define_solve(ModeParser& p) {
  CommandLine& c = p.line;
  CLI::App& app = p.app;
  app.add_option("SCENE", c.job.input.path,
                 "Scene: a description (.des) or a model (.obj, .ply, .gltf, .glb)")
      ->required();
  app.add_option("OUTPUT", c.job.outputs.mesh,
                 "Output mesh (.ply, .off, .gfo (COFF), .obj, .gltf or .glb)");
  bool& check = p.keep<bool>();
  app.add_flag("--check", check, "Parse and validate the scene, print a summary, do not solve");
  std::string& cross_check = p.keep<std::string>();
  app.add_option("--cross-check", cross_check,
                 "Solve with --backend and this backend too, compare their rays against brute "
                 "force and their vertices and radiosity; exit 1 if they disagree");
  SolvingMode& solving = p.keep<SolvingMode>();
  solving.add_to(app, c, /*time_limit=*/true, /*images=*/true, /*memory=*/true);
  app.add_option("--stats-json", c.job.stats_json, "Write run statistics as JSON to this file");
  const OptionGroup group(app, "Checkpoints");
  app.add_option("--checkpoint", c.job.checkpoint,
                 "Save the solver state to this file (every --checkpoint-every seconds, when "
                 "stopped by Ctrl-C or SIGTERM, and at the end); resume from it when it exists");
  app.add_option("--checkpoint-every", c.job.checkpoint_every,
                 "Seconds between checkpoints, 0 for after every shot")
      ->capture_default_str()
      ->check(non_negative());
  p.apply = [&solving, &check, &cross_check](CommandLine& r) {
    solving.apply(r);
    if (check) {
      // --check summarises a model without lamps and warns how to light it; the solve refuses.
      r.mode = Mode::Check;
      r.job.input.model.require_emission = false;
      r.job.input.model.warn_unlit = true;
    }
    // --max-shots 0 asks for the unlit scene: a model without lamps is what it writes.
    if (r.run.solver.max_shots == 0) r.job.input.model.require_emission = false;
    if (!cross_check.empty()) {
      if (check) throw CLI::ValidationError("--cross-check", "solves; --check does not");
      try {
        r.cross_check = parse_backend_kind(cross_check);
      } catch (const Error& e) {
        throw CLI::ValidationError("--cross-check", e.message());
      }
      r.mode = Mode::CrossCheck;
    }
    if (!r.job.checkpoint.empty() && r.mode != Mode::Solve) {
      throw CLI::ValidationError("--checkpoint", "applies to a solve that writes outputs");
    }
    if (r.mode == Mode::Solve && r.job.outputs.mesh.empty() && r.job.outputs.images.empty()) {
      throw CLI::RequiredError("OUTPUT (or --image, or --check)");
    }
  };
}

struct ModeDefinition {
  const char* word;   // the first argument that chooses it ("" for none)
  const char* title;  // how messages name it
  const char* usage;
  const char* help;
  void (*define)(ModeParser&);
};

const ModeDefinition kModes[] = {
    {"", "rad", "rad [options] SCENE OUTPUT", kOverview, define_solve},
    {"batch", "rad batch", "rad batch OUTDIR SCENE... [options]", kBatchHelp, define_batch},
    {"serve", "rad serve", "rad serve SCENE [options]", kServeHelp, define_serve},
    {"convert", "rad convert", "rad convert IN OUT [options]", kConvertHelp, define_convert},
};

std::unique_ptr<ModeParser> make_parser(const ModeDefinition& mode) {
  auto p = std::make_unique<ModeParser>(mode.help, mode.title);
  mode.define(*p);
  for (CLI::Option* o : p->app.get_options()) {
    const auto label = kValueLabels.find(
        "--" + (o->get_lnames().empty() ? std::string() : o->get_lnames().front()));
    if (label != kValueLabels.end()) o->option_text(label->second);
  }
  return p;
}

// "--max-shots expects a whole number, got 'five'" for CLI11's "Could not convert: --max-shots =
// five"; other messages as they are.
std::string conversion_message(const ModeParser& p, const std::string& what) {
  const std::string prefix = "Could not convert: ";
  const size_t equals = what.find(" = ");
  if (what.rfind(prefix, 0) != 0 || equals == std::string::npos) return what;
  const std::string name = what.substr(prefix.size(), equals - prefix.size());
  const std::string value = what.substr(equals + 3);
  const CLI::Option* o = p.app.get_option_no_throw(name);
  const std::string kind = o ? value_kind(*o) : "";
  const char* expected = kind == "INT"     ? "a whole number"
                         : kind == "UINT"  ? "a whole number, 0 or more"
                         : kind == "FLOAT" ? "a number"
                                           : "another value";
  return fmt::format("{} expects {}, got '{}'", name, expected, value);
}

// The first argument CLI11 left over that looks like an option ("--max-shot", "--max-shot=5",
// "-x"), without its value; empty if none does.
std::string first_unknown_option(const std::vector<std::string>& left_over) {
  for (const std::string& a : left_over) {
    if (a.size() < 2 || a[0] != '-' || a == "--") continue;
    if (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.') continue;  // -1, -.5
    return a.substr(0, a.find('='));
  }
  return {};
}

// What a usage error says: the offending argument first, then how to put it right.
std::string usage_message(const ModeDefinition& mode, const ModeParser& p, const std::string& what,
                          bool extras) {
  const std::vector<std::string> left_over = p.app.remaining();
  const std::string unknown = first_unknown_option(left_over);
  std::string line;
  if (!unknown.empty()) {
    line = fmt::format("{}: unknown option '{}'", mode.title, unknown);
    const ModeDefinition* owner = nullptr;
    for (const ModeDefinition& other : kModes) {
      const std::vector<std::string> names = make_parser(other)->option_names();
      if (&other != &mode && std::find(names.begin(), names.end(), unknown) != names.end()) {
        owner = &other;
        break;
      }
    }
    if (owner) {
      line += fmt::format(" ({} takes it; {} does not)", owner->usage, mode.title);
    } else if (const auto near = nearest_option(unknown, p.option_names())) {
      line += fmt::format("; did you mean '{}'?", *near);
    }
  } else if (extras && !left_over.empty()) {
    line = fmt::format("{}: unexpected argument '{}'", mode.title, left_over.front());
  } else {
    line = fmt::format("{}: {}", mode.title, what);
  }
  return fmt::format("{}\nUsage: {} ('{} --help' lists the options)\n", line, mode.usage,
                     mode.title);
}

// Parses `args` (the arguments after the mode's word) with the mode's parser, then checks and
// completes what they say; prints and returns nothing on --help, --version or a usage error.
std::optional<CommandLine> parse_mode(const ModeDefinition& mode, std::vector<std::string> args,
                                      int* exit_code) {
  std::unique_ptr<ModeParser> p = make_parser(mode);
  std::reverse(args.begin(), args.end());  // CLI11 takes them from the back
  std::string what;
  bool extras = false;
  try {
    p->app.parse(args);
    p->apply(p->line);
    return std::move(p->line);
  } catch (const CLI::Success& e) {  // --help, --version
    *exit_code = p->app.exit(e);
    return std::nullopt;
  } catch (const CLI::ExtrasError& e) {
    what = e.what(), extras = true;
  } catch (const CLI::ConversionError& e) {
    what = conversion_message(*p, e.what());
  } catch (const CLI::ParseError& e) {
    what = e.what();
  } catch (const Error& e) {
    what = e.loc().file.empty() ? e.message() : e.what();
  }
  std::fputs(usage_message(mode, *p, what, extras).c_str(), stderr);
  *exit_code = kExitUsage;
  return std::nullopt;
}

// The man page's part: its option entries made from the same definitions as --help.

// `text` with what man(7) reads otherwise escaped: a backslash, and a hyphen (an option's "--"
// is two minus signs, \-\-, which copy and search as typed).
std::string roff_escape(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    out += ch == '\\' ? "\\e" : ch == '-' ? "\\-" : std::string(1, ch);
  }
  return out;
}

// Escaped text as lines of the page's width; a line that would start with '.' or '\'' (a
// request) starts with the zero-width \& instead.
std::string roff_lines(const std::string& escaped) {
  std::string out;
  const std::string wrapped = wrap(escaped, 0, 96);
  for (size_t at = 0; at < wrapped.size();) {
    const size_t end = std::min(wrapped.find('\n', at), wrapped.size());
    const std::string line = wrapped.substr(at, end - at);
    if (!line.empty()) out += (line[0] == '.' || line[0] == '\'' ? "\\&" : "") + line + "\n";
    at = end + 1;
  }
  return out;
}

// One option as a tagged paragraph: its names in bold, its value in italics, then what --help
// says of it.
std::string man_entry(const CLI::Option& o) {
  std::vector<std::string> names;
  for (const std::string& s : o.get_snames()) names.push_back(roff_escape("-" + s));
  for (const std::string& l : o.get_lnames()) names.push_back(roff_escape("--" + l));
  std::string all;
  for (const std::string& n : names) all += (all.empty() ? "" : " \", \" ") + n;
  const std::string label = roff_escape(value_label(o));
  std::string head;
  if (label.empty()) {
    head = names.size() == 1 ? ".B " + all : ".BR " + all;
  } else if (names.size() == 1) {
    head = ".BI " + all + " \" " + label + "\"";
  } else {
    head = ".BR " + all + " \" \\fI" + label + "\\fR\"";
  }
  std::string text = option_description(o);
  if (!text.empty() && text.back() != '.') text += '.';  // a sentence, as the page's prose
  return ".TP\n" + head + "\n" + roff_lines(roff_escape(text));
}

// "\fB--a\fR, \fB--b\fR and \fB--c\fR".
std::string roff_option_list(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    out += (i == 0                  ? ""
            : i + 1 == names.size() ? " and "
                                    : ", ") +
           std::string("\\fB") + roff_escape(names[i]) + "\\fR";
  }
  return out;
}

// The option entries of rad(1): rad's options group by group as --help lists them, then for
// each other mode which of those it takes and its own (or its own description of one).
std::string man_options() {
  const auto rad = make_parser(kModes[0]);
  const auto generic = [](const std::string& names) {
    return names == "-h,--help" || names == "--version";
  };
  std::string out;
  std::vector<const CLI::Option*> rad_options;
  for (const std::string& group : rad->app.get_groups()) {
    bool any = false;
    for (const CLI::Option* o : rad->app.get_options()) {
      if (!o->nonpositional() || o->get_group() != group) continue;
      if (!any) out += ".SS " + (group == "Options" ? std::string("General") : group) + "\n";
      any = true;
      out += man_entry(*o);
      rad_options.push_back(o);
    }
  }
  for (size_t m = 1; m < std::size(kModes); ++m) {
    const auto p = make_parser(kModes[m]);
    std::vector<std::string> shared, left_out;
    std::string own;
    std::vector<std::string> here;
    for (const CLI::Option* o : p->app.get_options()) {
      if (!o->nonpositional()) continue;
      const std::string names = option_names(*o);
      here.push_back(names);
      const auto same = std::find_if(rad_options.begin(), rad_options.end(), [&](auto* r) {
        return option_names(*r) == names && value_label(*r) == value_label(*o) &&
               option_description(*r) == option_description(*o);
      });
      if (same == rad_options.end()) {
        own += man_entry(*o);
      } else if (!generic(names)) {
        shared.push_back(names);
      }
    }
    for (const CLI::Option* r : rad_options) {
      const std::string names = option_names(*r);
      if (!generic(names) && std::find(here.begin(), here.end(), names) == here.end()) {
        left_out.push_back(names);
      }
    }
    std::string takes = left_out.empty() ? "The options above"
                        : left_out.size() <= shared.size()
                            ? "The options above except " + roff_option_list(left_out)
                            : "Of the options above, " + roff_option_list(shared);
    takes += own.empty() ? "." : ", and:";
    out += ".SS \"" + roff_escape(kModes[m].title) + "\"\n" + roff_lines(takes) + own;
  }
  return out;
}

}  // namespace

std::string man_page_with_options(const std::string& page) {
  const std::string begin = ".\\\" BEGIN OPTIONS", end = ".\\\" END OPTIONS";
  const size_t b = page.find(begin), e = page.find(end);
  const size_t first = b == std::string::npos ? b : page.find('\n', b);
  if (first == std::string::npos || e == std::string::npos || e < first) {
    throw Error("the page has no lines '" + begin + "' and '" + end +
                "' around its option entries: add them where the entries go");
  }
  return page.substr(0, first + 1) + man_options() + page.substr(e);
}

size_t edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment (Damerau-Levenshtein without repeated edits of one substring):
  // typos drop, double, change or swap letters. Three rows suffice.
  std::vector<size_t> before(b.size() + 1), last(b.size() + 1), row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) last[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t change = a[i - 1] == b[j - 1] ? 0 : 1;
      row[j] = std::min({last[j] + 1, row[j - 1] + 1, last[j - 1] + change});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        row[j] = std::min(row[j], before[j - 2] + 1);
      }
    }
    std::swap(before, last);
    std::swap(last, row);
  }
  return last[b.size()];
}

std::optional<std::string> nearest_option(const std::string& typed,
                                          const std::vector<std::string>& names) {
  // Close enough to be the same word mistyped: about one edit in three letters, at most three.
  const size_t letters = typed.size() - std::min(typed.find_first_not_of('-'), typed.size());
  const size_t most = std::min<size_t>(3, letters / 3);
  std::optional<std::string> best;
  size_t best_distance = most + 1;
  for (const std::string& name : names) {
    const size_t d = edit_distance(typed, name);
    if (d < best_distance) best = name, best_distance = d;
  }
  return best;
}

std::optional<CommandLine> parse_command_line(int argc, char** argv, int* exit_code) {
  // The original's flags, spelled the modern way before CLI11 sees them.
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "-noshadows") a = "--no-shadows";
    if (a == "-minsize") a = "--min-size";
    args.push_back(a);
  }
  for (const ModeDefinition& mode : kModes) {
    if (*mode.word == '\0' || args.empty() || args.front() != mode.word) continue;
    return parse_mode(mode, std::vector<std::string>(args.begin() + 1, args.end()), exit_code);
  }
  return parse_mode(kModes[0], std::move(args), exit_code);
}

}  // namespace rad
