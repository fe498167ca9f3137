#include "lbm/petsc_log.hpp"

#include <petscsys.h>

namespace aniso::lbm {
namespace {

PetscLogStage stage(const char* name) {
  PetscLogStage id = -1;
  if (PetscLogStageGetId(name, &id) != 0 || id < 0) static_cast<void>(PetscLogStageRegister(name, &id));
  return id;
}

PetscLogEvent event(const char* name, PetscClassId class_id) {
  PetscLogEvent id = -1;
  if (PetscLogEventGetId(name, &id) != 0 || id < 0)
    static_cast<void>(PetscLogEventRegister(name, class_id, &id));
  return id;
}

} // namespace

LogEvents lbm_log_events() {
  PetscBool initialized = PETSC_FALSE;
  static_cast<void>(PetscInitialized(&initialized));
  LogEvents events;
  if (initialized != PETSC_TRUE) return events;
  PetscClassId class_id = 0;
  static_cast<void>(PetscClassIdRegister("aniso-lbm", &class_id));
  events.enabled = true;
  events.setup = stage("LBM set-up");
  events.time_loop = stage("LBM time loop");
  events.output = stage("LBM output");
  events.stream_collide = event("LBMStreamCollide", class_id);
  events.halo = event("LBMHalo", class_id);
  events.monitor = event("LBMMonitor", class_id);
  return events;
}

} // namespace aniso::lbm
