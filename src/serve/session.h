// The interactive solve: a solver thread that owns the SolverState, applies queued edits between
// shots and publishes immutable snapshots for any number of readers.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <variant>
#include <vector>

#include "export/output_mesh.h"
#include "serve/material_controls.h"
#include "serve/snapshot.h"
#include "solver/solver_state.h"

namespace rad {

struct SessionOptions {
  SolverOptions solver;  // converge and max_shots stop the stepping; time_limit is ignored
  bool ambient = true;   // display colours include Cohen's ambient term
  ToneCurve curve = ToneCurve::Clamp;
  float exposure = 0.0f;  // stops added to the automatic exposure
  /// Seconds between snapshots while shooting (0: every shot); stretched to 4x the time one
  /// snapshot takes to build, so a large mesh costs the solver at most a fifth of its time.
  double publish_interval = 0.1;
  size_t max_pending_edits = 256;  // edits queued beyond this are refused
  /// The scene's unit of length in metres (--unit): the hierarchy holds a point or spot light's
  /// intensity in candela per square unit, the page in candela.
  double metres_per_unit = 1.0;
};

/// Runs a progressive solve on its own thread and lets other threads edit it.
///
/// Threading: every public member may be called from any thread at any time, except state(),
/// which needs the solver thread stopped. Edits only append to a queue (a short lock); the solver
/// thread takes the queue between two shots and applies it there, so no edit ever waits for a
/// shot and no shot runs under a lock. Readers get std::shared_ptr<const Snapshot>: the solver
/// thread builds each snapshot privately and swaps it in under a mutex held for a pointer copy.
/// When the solve converges (or is paused) the thread sleeps until an edit arrives.
///
/// Edits continue the same solve (Chen, "Incremental Radiosity", SIGGRAPH 1990; see
/// solver/edits.h): a material edit becomes positive or negative unshot radiosity, a light's
/// edit positive or negative light it has still to shoot, a forced subdivision gathers every
/// logged shot again at the new vertices.
class Session {
 public:
  /// Prepares the solve and publishes the first snapshot (before any shot); start() runs it.
  /// `h` and `vis` must outlive the session.
  Session(const Hierarchy& h, const VisibilityBackend& vis, const SessionOptions& o);
  ~Session();  // stop()
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// Starts the solver thread (once).
  void start();
  /// Stops and joins the solver thread after its current shot; wakes snapshot waiters. Idempotent.
  void stop();

  // Edits, applied in order by the solver thread between shots. Each returns false when the
  // queue already holds max_pending_edits (nothing is queued then).

  /// Changes a Pure's material: `patch` over the controls last requested for it (so two quick
  /// partial edits combine). A pending material edit of the same object is replaced, not
  /// queued again (a slider's intermediate values cost nothing). Throws rad::Error when `object`
  /// is not a Pure or the resulting controls are out of range (see controls_error).
  bool edit_material(int32_t object, const MaterialPatch& patch);
  /// Changes light `light` (Hierarchy::lights) of the scene: `patch` over the controls last
  /// requested for it, intensity in candela or lux (LightControls). A pending edit of the same
  /// light is replaced, not queued again. Throws rad::Error when the light does not exist, the
  /// scene gave it intensity 0, or the resulting controls are out of range.
  bool edit_light(int32_t light, const LightPatch& patch);
  /// Splits every leaf of `polygon` one level (down to the minimum size), new vertices exact.
  /// Throws rad::Error for a polygon index out of range.
  bool subdivide(int32_t polygon);
  bool pause();
  bool resume();
  /// Starts the solve over from the unlit mesh: with the current materials and lights, or with
  /// the scene's own when `original_materials`. The exposure follows the solve again.
  bool restart(bool original_materials);
  /// Sets the user's exposure offset (stops, in [-20, 20]) and/or refits the automatic exposure
  /// to the current solution. Throws rad::Error for stops out of range.
  bool set_exposure(std::optional<float> stops, bool refit);
  /// Sets each light group's factor in the colours shown (one per group, in [0, 100]): the
  /// groups' radiosities mixed, without a new solve. Throws rad::Error for another count or a
  /// factor out of range.
  bool set_dimmers(std::vector<float> dimmers);

  /// The latest snapshot (never null).
  std::shared_ptr<const Snapshot> snapshot() const;
  /// Waits until a snapshot newer than `version` is published, the session stops, or `timeout`
  /// passes; returns the latest snapshot either way.
  std::shared_ptr<const Snapshot> wait_for_snapshot(uint64_t version,
                                                    std::chrono::milliseconds timeout) const;
  /// True once stop() has been called.
  bool stopped() const;

  /// The solver state; only while the solver thread is not running (before start, after stop).
  const SolverState& state() const { return state_; }
  const Hierarchy& hierarchy() const { return h_; }
  const SessionOptions& options() const { return options_; }

 private:
  struct MaterialEdit {
    int32_t object;
    MaterialControls controls;
  };
  struct LightEdit {
    int32_t light;
    LightControls controls;
  };
  struct SubdivideEdit {
    int32_t polygon;
  };
  struct PauseEdit {
    bool pause;
  };
  struct RestartEdit {
    bool original_materials;
  };
  struct ExposureEdit {
    std::optional<float> stops;
    bool refit;
  };
  struct DimmerEdit {
    std::vector<float> dimmers;
  };
  using Edit = std::variant<MaterialEdit, LightEdit, SubdivideEdit, PauseEdit, RestartEdit,
                            ExposureEdit, DimmerEdit>;

  bool enqueue(Edit e);  // with mutex_ held by the caller
  void run();            // the solver thread
  void apply(const Edit& e);
  bool finished() const;
  void apply_light(int32_t light);  // light_controls_[light] into the solver state
  void publish();

  const Hierarchy& h_;
  const VisibilityBackend& vis_;
  const SessionOptions options_;
  std::vector<MaterialControls> original_controls_;     // per object, from the scene
  std::vector<LightControls> original_light_controls_;  // per light, from the scene

  // Solver thread only (and state() while it is not running).
  SolverState state_;
  std::vector<MaterialControls> controls_;     // per object, as applied
  std::vector<LightControls> light_controls_;  // per light, as applied
  bool paused_ = false;
  bool nothing_to_shoot_ = false;
  bool exposure_locked_ = false;
  bool refit_pending_ = false;
  float exposure_stops_ = 0.0f;
  float base_scale_ = 1.0f;     // the automatic exposure, before the user's stops
  std::vector<float> dimmers_;  // per light group, its factor in the colours shown
  std::string notice_;
  OutputMeshBuilder builder_;
  uint64_t version_ = 0, mesh_version_ = 0;
  std::chrono::steady_clock::time_point last_publish_, rate_mark_time_;
  uint64_t rate_mark_rays_ = 0;
  double rays_per_second_ = 0.0;
  double solve_seconds_ = 0.0;    // stepping time since the (re)start
  double publish_seconds_ = 0.0;  // how long the last snapshot took to build

  // Guarded by mutex_: the edit queue and what it was last asked.
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Edit> queue_;
  std::vector<MaterialControls> requested_controls_;
  std::vector<LightControls> requested_light_controls_;
  bool stopping_ = false;
  bool started_ = false;

  // Guarded by snapshot_mutex_: the published snapshot.
  mutable std::mutex snapshot_mutex_;
  mutable std::condition_variable snapshot_changed_;
  std::shared_ptr<const Snapshot> snapshot_;
  std::atomic<bool> stopped_{false};  // set under snapshot_mutex_ so waiters cannot miss it

  std::thread thread_;
};

}  // namespace rad
