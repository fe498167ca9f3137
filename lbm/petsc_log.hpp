#pragma once
// PETSc profiling hooks: a stage per phase (set-up, time loop, output) and
// events inside the time loop (stream-collide, halo, monitor), so that
// -log_view attributes the wall time. Harmless when PETSc is not initialized.

#include <petsclog.h>

namespace aniso::lbm {

struct LogEvents {
  bool enabled = false;
  PetscLogStage setup = 0;
  PetscLogStage time_loop = 0;
  PetscLogStage output = 0;
  PetscLogEvent stream_collide = 0;
  PetscLogEvent halo = 0;
  PetscLogEvent monitor = 0;
};

/// Looks the stages and events up, registering them on first use.
LogEvents lbm_log_events();

/// Pushes a stage for the lifetime of the object.
class ScopedStage {
public:
  ScopedStage(const LogEvents& events, PetscLogStage stage) : enabled_(events.enabled) {
    if (enabled_) static_cast<void>(PetscLogStagePush(stage));
  }
  ~ScopedStage() {
    if (enabled_) static_cast<void>(PetscLogStagePop());
  }
  ScopedStage(const ScopedStage&) = delete;
  ScopedStage& operator=(const ScopedStage&) = delete;

private:
  bool enabled_;
};

/// Brackets one event occurrence.
class ScopedEvent {
public:
  ScopedEvent(const LogEvents& events, PetscLogEvent event) : enabled_(events.enabled), event_(event) {
    if (enabled_) static_cast<void>(PetscLogEventBegin(event_, 0, 0, 0, 0));
  }
  ~ScopedEvent() {
    if (enabled_) static_cast<void>(PetscLogEventEnd(event_, 0, 0, 0, 0));
  }
  ScopedEvent(const ScopedEvent&) = delete;
  ScopedEvent& operator=(const ScopedEvent&) = delete;

private:
  bool enabled_;
  PetscLogEvent event_;
};

} // namespace aniso::lbm
