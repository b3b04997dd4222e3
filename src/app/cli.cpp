#include "app/cli.h"

#include <fmt/format.h>
#include <tbb/info.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "core/error.h"
#include "core/memory.h"
#include "export/image_render.h"
#include "solver/ranks.h"

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

// --emit and --hierarchy: how a scene file is read, for the solving modes and rad convert alike.
struct SceneReading {
  std::vector<std::string> emit;
  std::string hierarchy;

  void add_to(CLI::App& app, const char* emit_help, const char* hierarchy_help) {
    app.add_option("--emit", emit, emit_help)
        ->expected(1)
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    app.add_option("--hierarchy", hierarchy, hierarchy_help);
  }
  // After parsing; throws CLI::ValidationError naming the option.
  void apply(CommandLine& c) const {
    try {
      for (const std::string& e : emit) c.model.emit.push_back(parse_emit_rule(e));
    } catch (const Error& e) {
      throw CLI::ValidationError("--emit", e.what());
    }
    try {
      if (!hierarchy.empty()) c.hierarchy = parse_hierarchy_mode(hierarchy);
    } catch (const Error& e) {
      throw CLI::ValidationError("--hierarchy", e.what());
    }
  }
};

// rad convert IN OUT: a mode of its own, with only the options it uses (a solve's would be
// silently meaningless here).
std::optional<CommandLine> parse_convert(std::vector<std::string> args, int* exit_code) {
  CommandLine c;
  c.convert = true;
  c.model.require_emission = false;
  CLI::App app{
      "rad convert: a scene (description, OBJ, glTF or PLY) written in another of those\n"
      "formats: geometry, materials and as much of the hierarchy as the target holds.\n\n"
      "  rad convert IN OUT [--emit 'PATTERN=VALUE']...\n",
      "rad convert"};
  app.add_option("in", c.scene, "Scene to read: .des, .obj, .gltf, .glb or .ply")->required();
  app.add_option("out", c.output, "Scene to write: .des, .obj (+ .mtl), .gltf, .glb or .ply")
      ->required();
  SceneReading reading;
  reading.add_to(app,
                 "For a model: materials matching the pattern emit VALUE times their colour "
                 "(repeatable)",
                 "file (as read: a model's groups and materials), auto (the Pures regrouped "
                 "into compact Composites and Assemblies of what is near) or flat; default file");
  app.add_flag("-q,--quiet", c.quiet, "Print errors only");
  std::reverse(args.begin(), args.end());
  try {
    app.parse(args);
    reading.apply(c);
  } catch (const CLI::ParseError& e) {
    *exit_code = app.exit(e);
    return std::nullopt;
  }
  return c;
}

}  // namespace

int thread_count(const CommandLine& cmd) {
  if (cmd.threads > 0) return cmd.threads;
  // A process bound to some cores (mpirun binds each rank) uses those; an unbound one shares
  // the machine with the other ranks on it.
  const int cores = tbb::info::default_concurrency();
  if (cores < int(std::thread::hardware_concurrency())) return cores;
  return std::max(1, cores / local_rank_count());
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
  if (!args.empty() && args.front() == "convert") {
    return parse_convert(std::vector<std::string>(args.begin() + 1, args.end()), exit_code);
  }
  CommandLine c;
  c.batch = !args.empty() && args.front() == "batch";
  if (c.batch) args.erase(args.begin());
  c.serve = !args.empty() && args.front() == "serve";
  if (c.serve) args.erase(args.begin());
  std::reverse(args.begin(), args.end());  // CLI11 parses a reversed vector

  std::string backend = "embree", method = "analytic", tonemap = "clamp";
  int samples = 16, max_samples = 64;
  CLI::App app{
      "rad: diffuse interreflection (radiosity) by progressive shooting with ray-traced\n"
      "vertex-to-source form factors and adaptive subdivision.\n\n"
      "  rad [options] SCENE.des OUTPUT.ply      solve and write every vertex's colour\n"
      "  rad --check SCENE.des                   parse, validate and summarise only\n"
      "  rad --cross-check BACKEND SCENE.des     solve with --backend and BACKEND; report\n"
      "                                          every disagreement (rays and radiosity)\n"
      "  rad batch OUTDIR SCENE... [options]     solve many scenes (SCENE may be a .txt list\n"
      "                                          of .des files); outputs and stats in OUTDIR\n"
      "  rad convert IN OUT                      the scene itself in another format (.des,\n"
      "                                          .obj, .gltf, .glb, .ply); rad convert --help\n"
      "  rad serve SCENE.des [--port P] [--host H] [--output FILE]\n"
      "                                          solve in the background and watch, edit and\n"
      "                                          export it in a browser (loopback by default);\n"
      "                                          Ctrl-C stops and writes --output/--image\n",
      "rad"};
  std::string formats = "ply,png", shard;
  if (c.batch) {
    app.add_option("--shard", shard,
                   "Solve this process's share of the list: I/N takes scenes I, I + N, I + 2N, "
                   "... (0 <= I < N); 'slurm' takes I and N from the Slurm job array "
                   "(SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN, SLURM_ARRAY_TASK_COUNT)");
    app.add_option("outdir", c.batch_dir, "Folder for every scene's outputs and stats")->required();
    app.add_option("scenes", c.batch_scenes, "Scene files, or .txt files listing them")->required();
    app.add_option("--formats", formats,
                   "Outputs per scene, by extension: mesh (ply, off, obj, gltf, glb) and image "
                   "(png, hdr, exr, pfm)")
        ->capture_default_str();
  } else if (c.serve) {
    app.add_option("scene", c.scene, "Scene description file")->required();
    app.add_option("--port", c.port, "rad serve: TCP port (0: any free port)")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    app.add_option("--host", c.host,
                   "rad serve: address to listen on (other than loopback exposes the scene and "
                   "its edits to the network)")
        ->capture_default_str();
    app.add_option("--output", c.output,
                   "rad serve: mesh written when the server stops (.ply, .off, .obj, .gltf, .glb)");
  } else {
    app.add_option("scene", c.scene, "Scene: a description (.des) or a model (.obj, .ply)")
        ->required();
    app.add_option("output", c.output,
                   "Output mesh (.ply, .off, .gfo (COFF), .obj, .gltf or .glb)");
  }
  app.add_flag("--check", c.check, "Parse and validate the scene, print a summary, do not solve");

  app.add_option("--backend", backend, "Shadow-ray backend: embree, grid or brute")
      ->capture_default_str();
  std::string cross_check;
  app.add_option("--cross-check", cross_check,
                 "Solve with --backend and this backend too, compare their rays against brute "
                 "force and their vertices and radiosity; exit 1 if they disagree");
  app.add_flag("!--no-packets", c.packets, "Trace shadow rays one at a time (Embree)");
  app.add_option("--threads", c.threads, "Worker threads (0 = all cores)")->capture_default_str();
  app.add_flag("!--no-shadows", c.solver.shadows, "No shadow rays: every visibility term is 1");
  app.add_option("--min-size", c.solver.min_size,
                 "Smallest element edge, scene units (default: scene diagonal / 256)");
  app.add_option("--max-size", c.solver.max_size,
                 "Largest element edge of the initial mesh, scene units (default: scene "
                 "diagonal / 16, at least 2 x --min-size)");
  app.add_option("--samples", samples,
                 "Fewest samples per shooting cluster (a square: 1, 4, 9, 16, ... up to 256)")
      ->capture_default_str();
  app.add_option("--max-samples", max_samples,
                 "Most samples per shooting cluster (a square, up to 256): a big source gets more "
                 "than --samples, as many as bring their spacing within the initial mesh's "
                 "element size (scene diagonal / 16) or this many; give both to fix the count")
      ->capture_default_str();
  app.add_option("--form-factor", method,
                 "analytic (exact unoccluded form factor x sampled visibility) or samples "
                 "(EQ 7 sums, as the original)")
      ->capture_default_str();
  app.add_option("--threshold", c.solver.subdivision_threshold,
                 "Subdivision limit: split where vertices differ by more than this fraction of "
                 "the scene's radiosity scale (emitted power / total area)")
      ->capture_default_str();
  app.add_option("--intensity-cut", c.solver.intensity_cut,
                 "No shadow rays when a vertex's unoccluded gain is below this fraction of the "
                 "radiosity scale")
      ->capture_default_str();
  app.add_option("--converge", c.solver.converge,
                 "Stop when unshot energy <= this fraction of the emitted energy")
      ->capture_default_str();
  app.add_option("--max-shots", c.solver.max_shots,
                 "Stop after this many shots (0 writes the unlit scene: emission only)");
  app.add_option("--time-limit", c.solver.time_limit, "Stop after this many seconds");
  app.add_flag("--overshoot", c.solver.overshoot,
               "Overshooting (Feda & Purgathofer 1992): shooters also shoot their share of the "
               "ambient term");
  app.add_flag("--ascii", c.ascii, "Write text PLY instead of binary");
  app.add_flag("!--no-ambient", c.ambient,
               "Display colours without Cohen's ambient term (the stored radiosity never has it)");
  app.add_option("--tonemap", tonemap, "Display tone curve: clamp, reinhard or aces")
      ->capture_default_str();
  app.add_option("--exposure", c.exposure, "Stops added to the automatic exposure")
      ->capture_default_str();
  std::string camera, size = "800x800";
  // One value per --image (repeat the option for more images): a vector option would otherwise
  // swallow the positionals after it (`--image out.png scene.des out.ply`).
  app.add_option("--image", c.images,
                 "Render the solved scene to this image: .png (tone-mapped sRGB) or linear "
                 ".hdr, .exr, .pfm (repeatable)")
      ->expected(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("--camera", camera,
                 "Image camera eye_x,eye_y,eye_z,target_x,target_y,target_z[,fov_deg], up +y "
                 "(default: frames the scene from its open side; fov 39.3)");
  app.add_option("--size", size, "Image size WxH in pixels")->capture_default_str();
  app.add_option("--stats-json", c.stats_json, "Write run statistics as JSON to this file");
  app.add_option("--checkpoint", c.checkpoint,
                 "Save the solver state to this file (every --checkpoint-every seconds, when "
                 "stopped by Ctrl-C or SIGTERM, and at the end); resume from it when it exists");
  app.add_option("--checkpoint-every", c.checkpoint_every,
                 "Seconds between checkpoints (0: after every shot)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  SceneReading reading;
  reading.add_to(app,
                 "For a model scene (.obj, .ply, .gltf, .glb): materials matching the pattern "
                 "emit VALUE times their colour, e.g. --emit 'Lamp*=12' (repeatable)",
                 "Object hierarchy (SPEC §3): file (as written), auto (Pures regrouped into "
                 "compact Composites and Assemblies of what is near) or flat (one Composite); "
                 "default auto for models, file for descriptions");
  std::string max_memory;
  app.add_option("--max-memory", max_memory,
                 "Memory the solve may use (512M, 8G, ...; default 90% of the machine's): a scene "
                 "that could need more is refused; a solve that reaches it stops and writes");
  app.add_flag("-q,--quiet", c.quiet, "Print errors only");
  try {
    app.parse(args);
    c.backend = parse_backend_kind(backend);
    reading.apply(c);
    try {
      if (!max_memory.empty()) c.max_memory = parse_byte_size(max_memory);
    } catch (const Error& e) {
      throw CLI::ValidationError("--max-memory", e.what());
    }
    if (!cross_check.empty()) {
      c.cross_check = parse_backend_kind(cross_check);
      if (c.batch || c.serve || c.check) {
        throw CLI::ValidationError("--cross-check", "applies to one scene from the command line");
      }
    }
    c.tonemap = parse_tone_curve(tonemap);
    try {
      if (!camera.empty()) c.camera = parse_camera(camera);
    } catch (const Error& e) {
      throw CLI::ValidationError("--camera", e.what());
    }
    char x = 0, end = 0;
    if (std::sscanf(size.c_str(), "%d%c%d%c", &c.image_width, &x, &c.image_height, &end) != 3 ||
        x != 'x' || c.image_width < 1 || c.image_height < 1 || c.image_width > kMaxImageSize ||
        c.image_height > kMaxImageSize) {
      throw CLI::ValidationError(
          "--size", fmt::format("expected WxH in pixels (1 to {}), got {}", kMaxImageSize, size));
    }
    if (method == "analytic") {
      c.solver.method = FormFactorMethod::Analytic;
    } else if (method == "samples") {
      c.solver.method = FormFactorMethod::Samples;
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
    c.solver.sample_grid = grid(samples, "--samples");
    c.solver.max_sample_grid = std::max(grid(max_samples, "--max-samples"), c.solver.sample_grid);
    if (!shard.empty()) {
      try {
        parse_shard(shard, &c.shard_index, &c.shard_count);
      } catch (const Error& e) {
        throw CLI::ValidationError("--shard", e.what());
      }
    }
    c.batch_formats.clear();
    for (size_t at = 0; at <= formats.size();) {
      const size_t comma = std::min(formats.find(',', at), formats.size());
      if (comma > at) c.batch_formats.push_back(formats.substr(at, comma - at));
      at = comma + 1;
    }
    if (!c.checkpoint.empty() && (c.batch || c.serve || c.check)) {
      throw CLI::ValidationError("--checkpoint",
                                 "applies to one scene solved from the command line");
    }
    if (!c.check && !c.cross_check && !c.batch && !c.serve && c.output.empty() &&
        c.images.empty()) {
      throw CLI::RequiredError("output (or --image, or --check)");
    }
  } catch (const CLI::ParseError& e) {
    *exit_code = app.exit(e);
    return std::nullopt;
  }
  return c;
}

}  // namespace rad
