#include "serve/session.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "export/exposure.h"
#include "serve/requests.h"
#include "solver/edits.h"
#include "solver/light_groups.h"
#include "solver/solver.h"

namespace rad {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

constexpr size_t kHistoryPoints = 256;
constexpr float kMaxStops = 20.0f;

}  // namespace

Session::Session(const Hierarchy& h, const VisibilityBackend& vis, const SessionOptions& o)
    : h_(h), vis_(vis), options_(o), state_(make_solver_state(h, o.solver)) {
  original_controls_.reserve(h.objects.size());
  for (const SceneObject& obj : h.objects) original_controls_.push_back(to_controls(obj.material));
  controls_ = original_controls_;
  requested_controls_ = original_controls_;
  const double square = o.metres_per_unit * o.metres_per_unit;
  for (const Light& l : h.lights) original_light_controls_.push_back(to_light_controls(l, square));
  light_controls_ = original_light_controls_;
  requested_light_controls_ = original_light_controls_;
  exposure_stops_ = o.exposure;
  last_publish_ = rate_mark_time_ = Clock::now();
  publish();
}

Session::~Session() { stop(); }

void Session::start() {
  std::lock_guard lock(mutex_);
  if (started_ || stopping_) return;
  started_ = true;
  thread_ = std::thread([this] { run(); });
}

void Session::stop() {
  {
    std::lock_guard lock(snapshot_mutex_);
    stopped_ = true;
  }
  snapshot_changed_.notify_all();
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

bool Session::stopped() const { return stopped_; }

bool Session::enqueue(Edit e) {
  if (queue_.size() >= options_.max_pending_edits) return false;
  queue_.push_back(std::move(e));
  wake_.notify_one();
  return true;
}

bool Session::edit_material(int32_t object, const MaterialPatch& patch) {
  if (!is_pure(h_, object)) {
    throw Error(fmt::format("object {} is not a Pure", object));
  }
  std::lock_guard lock(mutex_);
  const MaterialControls c = apply_patch(requested_controls_[size_t(object)], patch);
  if (auto why = controls_error(c)) throw Error(*why);
  for (Edit& e : queue_) {
    if (auto* m = std::get_if<MaterialEdit>(&e); m && m->object == object) {
      m->controls = c;
      requested_controls_[size_t(object)] = c;
      wake_.notify_one();
      return true;
    }
  }
  if (!enqueue(MaterialEdit{object, c})) return false;
  requested_controls_[size_t(object)] = c;
  return true;
}

bool Session::edit_light(int32_t light, const LightPatch& patch) {
  if (light < 0 || size_t(light) >= h_.lights.size()) {
    throw Error(fmt::format("light {} does not exist (the scene has {})", light, h_.lights.size()));
  }
  std::lock_guard lock(mutex_);
  const LightControls c = apply_patch(requested_light_controls_[size_t(light)], patch);
  if (auto why = controls_error(c)) throw Error(*why);
  for (Edit& e : queue_) {
    if (auto* l = std::get_if<LightEdit>(&e); l && l->light == light) {
      l->controls = c;
      requested_light_controls_[size_t(light)] = c;
      wake_.notify_one();
      return true;
    }
  }
  if (!enqueue(LightEdit{light, c})) return false;
  requested_light_controls_[size_t(light)] = c;
  return true;
}

bool Session::subdivide(int32_t polygon) {
  if (polygon < 0 || size_t(polygon) >= h_.triangles.size()) {
    throw Error(
        fmt::format("polygon {} does not exist (the scene has {})", polygon, h_.triangles.size()));
  }
  std::lock_guard lock(mutex_);
  return enqueue(SubdivideEdit{polygon});
}

bool Session::pause() {
  std::lock_guard lock(mutex_);
  return enqueue(PauseEdit{true});
}

bool Session::resume() {
  std::lock_guard lock(mutex_);
  return enqueue(PauseEdit{false});
}

bool Session::restart(bool original_materials) {
  std::lock_guard lock(mutex_);
  if (!enqueue(RestartEdit{original_materials})) return false;
  if (original_materials) {
    requested_controls_ = original_controls_;
    requested_light_controls_ = original_light_controls_;
  }
  return true;
}

bool Session::set_exposure(std::optional<float> stops, bool refit) {
  if (stops && !(std::abs(*stops) <= kMaxStops)) {
    throw Error(
        fmt::format("exposure is {} stops; it must be in [-{}, {}]", *stops, kMaxStops, kMaxStops));
  }
  std::lock_guard lock(mutex_);
  return enqueue(ExposureEdit{stops, refit});
}

bool Session::set_dimmers(std::vector<float> dimmers) {
  const size_t groups = light_groups_kept(h_).size();
  if (dimmers.size() != groups) {
    throw Error(fmt::format("{} dimmers for {} light groups", dimmers.size(), groups));
  }
  for (float d : dimmers) {
    if (!(d >= 0.0f && d <= kMaxDimmer)) {
      throw Error(fmt::format("a dimmer is {}; it must be in [0, {}]", d, kMaxDimmer));
    }
  }
  std::lock_guard lock(mutex_);
  return enqueue(DimmerEdit{std::move(dimmers)});
}

std::shared_ptr<const Snapshot> Session::snapshot() const {
  std::lock_guard lock(snapshot_mutex_);
  return snapshot_;
}

std::shared_ptr<const Snapshot> Session::wait_for_snapshot(
    uint64_t version, std::chrono::milliseconds timeout) const {
  std::unique_lock lock(snapshot_mutex_);
  snapshot_changed_.wait_for(lock, timeout,
                             [&] { return snapshot_->version > version || stopped_; });
  return snapshot_;
}

bool Session::finished() const { return nothing_to_shoot_ || goal_reached(state_).has_value(); }

void Session::run() {
  bool dirty = false;  // shots since the last snapshot
  for (;;) {
    const bool idle = paused_ || finished();
    if (idle && dirty) {
      publish();
      dirty = false;
    }
    std::vector<Edit> edits;
    {
      std::unique_lock lock(mutex_);
      if (idle) wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (stopping_) break;
      edits.swap(queue_);
    }
    if (!edits.empty()) {
      for (const Edit& e : edits) apply(e);
      publish();
      dirty = false;
      continue;
    }
    const auto t = Clock::now();
    if (!step(state_, vis_)) nothing_to_shoot_ = true;
    solve_seconds_ += seconds_between(t, Clock::now());
    dirty = true;
    // Snapshots of a large mesh take time: at most a fifth of the solver thread goes to them.
    const double interval = std::max(options_.publish_interval, 4.0 * publish_seconds_);
    if (seconds_between(last_publish_, Clock::now()) >= interval) {
      publish();
      dirty = false;
    }
  }
  publish();  // Stopped
}

void Session::apply_light(int32_t light) {
  const Light& l = h_.lights[size_t(light)];
  const LightControls& c = light_controls_[size_t(light)];
  // The scene's own values exactly when the controls are back at them: nothing left to shoot.
  const LightSetting to =
      c == original_light_controls_[size_t(light)]
          ? LightSetting{l.colour, l.intensity}
          : to_light_setting(c, l.kind, options_.metres_per_unit * options_.metres_per_unit);
  rad::set_light(state_.solution, state_.energy, light, to.colour, to.intensity);
}

void Session::apply(const Edit& edit) {
  try {
    if (const auto* m = std::get_if<MaterialEdit>(&edit)) {
      // The exposure the user was looking at stays, so the edit shows as brighter or darker.
      exposure_locked_ = true;
      rad::set_material(edit_context(state_), m->object, to_material(m->controls), vis_);
      controls_[size_t(m->object)] = m->controls;
      nothing_to_shoot_ = false;
      notice_ = fmt::format(
          "'{}': colour ({:.3g}, {:.3g}, {:.3g}), reflectivity {:.3g}, "
          "emission {:.4g}",
          h_.objects[size_t(m->object)].name, m->controls.colour.x, m->controls.colour.y,
          m->controls.colour.z, m->controls.reflectivity, m->controls.emission);
    } else if (const auto* l = std::get_if<LightEdit>(&edit)) {
      exposure_locked_ = true;  // as for a material: the change shows as brighter or darker
      const LightControls before = light_controls_[size_t(l->light)];
      light_controls_[size_t(l->light)] = l->controls;
      try {
        apply_light(l->light);
      } catch (...) {
        light_controls_[size_t(l->light)] = before;
        throw;
      }
      nothing_to_shoot_ = false;
      const Light& light = h_.lights[size_t(l->light)];
      notice_ =
          l->controls.intensity > 0.0f
              ? fmt::format("light '{}': colour ({:.3g}, {:.3g}, {:.3g}), intensity {:.4g} {}",
                            light.name, l->controls.colour.x, l->controls.colour.y,
                            l->controls.colour.z, l->controls.intensity, intensity_unit(light.kind))
              : fmt::format("light '{}' off", light.name);
    } else if (const auto* s = std::get_if<SubdivideEdit>(&edit)) {
      const size_t n = force_subdivide(edit_context(state_), s->polygon, vis_);
      nothing_to_shoot_ = false;
      const std::string& name = h_.objects[size_t(h_.triangles.object[size_t(s->polygon)])].name;
      notice_ =
          n > 0
              ? fmt::format("polygon {} of '{}': {} new exact vertices", s->polygon, name, n)
              : fmt::format("polygon {} of '{}' is already at the minimum size", s->polygon, name);
    } else if (const auto* p = std::get_if<PauseEdit>(&edit)) {
      paused_ = p->pause;
      notice_ = paused_ ? "paused" : "resumed";
    } else if (const auto* r = std::get_if<RestartEdit>(&edit)) {
      state_ = make_solver_state(h_, options_.solver);
      builder_.reset();
      if (r->original_materials) {
        controls_ = original_controls_;
        light_controls_ = original_light_controls_;
      }
      // A fresh state holds the scene's materials: re-apply the edited ones before any shot
      // (emission changes become the initial unshot radiosity, exactly).
      for (size_t o = 0; o < h_.objects.size(); ++o) {
        if (h_.objects[o].kind == ObjectKind::Pure && !(controls_[o] == original_controls_[o])) {
          rad::set_material(edit_context(state_), int32_t(o), to_material(controls_[o]), vis_);
        }
      }
      // The same for the lights: an edit before their first shot changes what they shoot.
      for (size_t i = 0; i < h_.lights.size(); ++i) {
        if (!(light_controls_[i] == original_light_controls_[i])) apply_light(int32_t(i));
      }
      nothing_to_shoot_ = false;
      exposure_locked_ = false;
      solve_seconds_ = 0.0;
      rate_mark_rays_ = 0;
      rate_mark_time_ = Clock::now();
      notice_ = r->original_materials ? "restarted with the scene's materials and lights"
                                      : "restarted with the current materials and lights";
    } else if (const auto* d = std::get_if<DimmerEdit>(&edit)) {
      dimmers_ = d->dimmers;
      std::string list;
      for (float f : dimmers_) list += fmt::format("{}{:.3g}", list.empty() ? "" : ", ", f);
      notice_ = fmt::format("light groups dimmed to {}", list);
    } else if (const auto* x = std::get_if<ExposureEdit>(&edit)) {
      if (x->stops) exposure_stops_ = *x->stops;
      if (x->refit) exposure_locked_ = false;  // refitted by the next publish, then locked
      if (x->refit) refit_pending_ = true;
      notice_ = fmt::format("exposure {:+.2g} stops{}", exposure_stops_,
                            x->refit ? ", refitted to the current solution" : "");
    }
  } catch (const std::exception& e) {
    notice_ = fmt::format("edit failed: {}", e.what());
  }
}

void Session::publish() {
  const auto start = Clock::now();
  auto snap = std::make_shared<Snapshot>();
  bool geometry_changed = false;
  snap->mesh.geometry = builder_.update(state_, &geometry_changed);
  if (geometry_changed) ++mesh_version_;
  builder_.values(state_,
                  options_.ambient ? ambient_radiosity(state_.energy, state_.solution) : Vec3(0.0f),
                  snap->mesh);
  bool stop_requested = false;
  {
    std::lock_guard lock(mutex_);
    stop_requested = stopping_;
  }
  const bool done = finished();
  snap->status = stop_requested ? SessionStatus::Stopped
                 : paused_      ? SessionStatus::Paused
                 : done         ? SessionStatus::Converged
                                : SessionStatus::Running;
  if (!exposure_locked_) {
    base_scale_ = scene_tone_map(state_, snap->mesh.display, options_.curve, 0.0f).scale;
    // Fixed from the first convergence (or a refit) on, so later edits show as they are.
    if (done || refit_pending_) exposure_locked_ = true;
    refit_pending_ = false;
  }
  snap->tone.curve = options_.curve;
  snap->tone.scale = base_scale_ * std::exp2(exposure_stops_);
  snap->exposure_stops = exposure_stops_;
  snap->exposure_locked = exposure_locked_;

  const auto now = Clock::now();
  const uint64_t rays = state_.stats.rays.rays;
  if (snap->status != SessionStatus::Running) {
    rays_per_second_ = 0.0;
    rate_mark_time_ = now;
    rate_mark_rays_ = rays;
  } else if (const double dt = seconds_between(rate_mark_time_, now); dt >= 0.5) {
    rays_per_second_ = double(rays - rate_mark_rays_) / dt;
    rate_mark_time_ = now;
    rate_mark_rays_ = rays;
  }

  snap->version = ++version_;
  snap->mesh_version = mesh_version_;
  snap->shots = state_.shots.count;
  snap->unshot_fraction = state_.energy.unshot_fraction();
  snap->rays_per_second = rays_per_second_;
  snap->seconds = solve_seconds_;
  snap->build_seconds = publish_seconds_;
  // Light groups: their radiosities in the snapshot's mesh (so its exports hold them), and
  // dimmed, the colours shown mix them, each with its own part of the ambient term, each times
  // its dimmer (the groups' sum at 1 is the whole solve).
  const size_t groups = state_.solution.group_count;
  if (dimmers_.size() != groups) dimmers_.assign(groups, 1.0f);
  snap->dimmers = dimmers_;
  if (groups > 0) {
    snap->mesh.group_names = light_groups_kept(h_);
    for (size_t g = 0; g < groups; ++g) {
      snap->mesh.group_radiosity.push_back(builder_.per_vertex(
          [&](size_t p, uint32_t v) { return state_.solution.group_radiosity(g, p, v); }));
    }
  }
  const bool dimmed =
      std::any_of(dimmers_.begin(), dimmers_.end(), [](float d) { return d != 1.0f; });
  std::vector<Vec3> rho, shown;
  if (dimmed) {
    if (options_.ambient) {
      rho = builder_.per_vertex(
          [&](size_t p, uint32_t v) { return state_.solution.reflectance(p, v); });
    }
    shown.assign(snap->mesh.display.size(), Vec3(0.0f));
    for (size_t g = 0; g < groups; ++g) {
      const Vec3 ambient =
          options_.ambient ? ambient_radiosity(state_.energy, state_.solution, int(g)) : Vec3(0.0f);
      for (size_t i = 0; i < shown.size(); ++i) {
        const Vec3 b =
            snap->mesh.group_radiosity[g][i] + (rho.empty() ? Vec3(0.0f) : rho[i] * ambient);
        shown[i] += b * dimmers_[g];
      }
    }
  }
  const std::vector<Vec3>& display = dimmed ? shown : snap->mesh.display;
  snap->colour.resize(display.size());
  for (size_t i = 0; i < display.size(); ++i) snap->colour[i] = tone_map(display[i], snap->tone);
  const std::vector<int64_t> elements = elements_per_object(state_);
  snap->objects.resize(h_.objects.size());
  for (size_t o = 0; o < h_.objects.size(); ++o) {
    snap->objects[o].elements = elements[o];
    snap->objects[o].controls = controls_[o];
  }
  snap->lights = light_controls_;
  snap->elements = 0;
  for (int32_t r : h_.roots) snap->elements += elements[size_t(r)];
  snap->history = thin_history(state_.shots.history, kHistoryPoints);
  snap->notice = notice_;

  {
    std::lock_guard lock(snapshot_mutex_);
    snapshot_ = std::move(snap);
  }
  snapshot_changed_.notify_all();
  last_publish_ = Clock::now();
  publish_seconds_ = seconds_between(start, last_publish_);
}

}  // namespace rad
