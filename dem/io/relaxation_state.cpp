#include "dem/io/relaxation_state.hpp"

#include "common/error.hpp"
#include "common/h5/file.hpp"
#include "common/units.hpp"
#include "dem/io/parameters.hpp"

#include <array>
#include <filesystem>
#include <span>

namespace aniso::dem::io {
namespace {

constexpr const char* group_name = "relaxation";
constexpr const char* minimising = "minimising";
constexpr const char* verifying = "verifying";
constexpr const char* escaping = "escaping";

void write_vector(h5::Group& group, const std::string& name, const Vec3& v, std::string_view units) {
  const std::array<double, 3> values{v[0], v[1], v[2]};
  group.write_dataset<double>(name, std::span<const double>(values), h5::Dims{3}, units, name);
}

Vec3 read_vector(const h5::Group& group, const std::string& name) {
  const std::vector<double> values = group.read_dataset<double>(name, h5::Dims{3});
  return {values[0], values[1], values[2]};
}

// The control, settings and watching the relaxation gives back when it ends.
void write_memory(h5::Group& group, const protocol::PhaseMemory& memory) {
  const model::CellControl& control = memory.control;
  write_vector(group, "strain_rate", control.strain_rate, units::per_second);
  write_vector(group, "target", control.target, "1/s (strain_rate axes) or Pa (stress axes)");
  write_vector(group, "servo_state", control.servo_state, "");
  std::array<std::uint8_t, 3> mode{};
  for (std::size_t a = 0; a < 3; ++a)
    mode[a] = control.mode[a] == model::AxisMode::stress ? 1 : 0;
  group.write_dataset<std::uint8_t>("mode", std::span<const std::uint8_t>(mode), h5::Dims{3}, "",
                                    "0 = strain_rate, 1 = stress");
  group.write_attribute<std::uint8_t>("hold_mean_stress", control.hold_mean_stress ? 1 : 0);
  group.write_attribute_with_units("mean_stress_target", control.mean_stress_target, units::pascal);
  group.write_attribute<std::uint8_t>("watched", memory.watched ? 1 : 0);
  group.write_attribute_with_units("time_step", memory.settings.time_step, units::second);
  for (const h5::Parameter& parameter : stored_parameters(memory.settings))
    group.write_attribute_with_units(parameter.name, parameter.value, parameter.unit);
}

protocol::PhaseMemory read_memory(const h5::Group& group) {
  protocol::PhaseMemory memory;
  model::CellControl& control = memory.control;
  control.strain_rate = read_vector(group, "strain_rate");
  control.target = read_vector(group, "target");
  control.servo_state = read_vector(group, "servo_state");
  const std::vector<std::uint8_t> mode = group.read_dataset<std::uint8_t>("mode", h5::Dims{3});
  for (std::size_t a = 0; a < 3; ++a)
    control.mode[a] = mode[a] != 0 ? model::AxisMode::stress : model::AxisMode::strain_rate;
  control.hold_mean_stress = group.read_attribute<std::uint8_t>("hold_mean_stress") != 0;
  control.mean_stress_target = group.read_attribute<double>("mean_stress_target");
  memory.watched = group.read_attribute<std::uint8_t>("watched") != 0;
  // The settings as a checkpoint's /parameters, read and range-checked the same way.
  h5::Checkpoint stored;
  stored.time_step = group.read_attribute<double>("time_step");
  for (h5::Parameter parameter : stored_parameters(SimulationSettings{})) {
    parameter.value = group.read_attribute<double>(parameter.name);
    stored.parameters.push_back(parameter);
  }
  memory.settings = settings_from_checkpoint(stored, group.where());
  return memory;
}

void write_relaxation(h5::Group& group, const InterruptedRelaxation& relaxation) {
  const protocol::RelaxationState& s = relaxation.state;
  group.write_attribute("command", relaxation.command);
  group.write_attribute("purpose", relaxation.purpose);
  group.write_attribute("strain", relaxation.strain);
  group.write_attribute("next_history", relaxation.next_history);
  group.write_attribute<std::int64_t>("next_checkpoint", relaxation.next_checkpoint);
  group.write_attribute<std::int64_t>("steps", s.steps);
  group.write_attribute("stage", s.verifying ? verifying : (s.escaping ? escaping : minimising));
  group.write_attribute<std::int64_t>("escaped", s.escaped);
  group.write_attribute<std::int32_t>("passed", s.passed);
  group.write_attribute_with_units("start_stress", s.start_stress, units::pascal);
  group.write_attribute<std::int64_t>("verified", s.verified);
  group.write_attribute<std::int64_t>("verifying_steps", s.verifying_steps);
  group.write_attribute<std::int32_t>("windows_left", s.windows_left);
  if (s.fire) {
    h5::Group fire = group.create_group("fire");
    fire.write_attribute_with_units("min_step", s.fire->min_step, units::second);
    fire.write_attribute_with_units("max_step", s.fire->max_step, units::second);
    fire.write_attribute("alpha", s.fire->alpha);
    fire.write_attribute<std::int32_t>("downhill", s.fire->n_downhill);
    fire.write_attribute<std::int64_t>("stops", s.fire->stops);
  }
  h5::Group given_back = group.create_group("given_back");
  write_memory(given_back, s.memory);
}

InterruptedRelaxation read_relaxation(const h5::Group& group) {
  InterruptedRelaxation relaxation;
  protocol::RelaxationState& s = relaxation.state;
  relaxation.command = group.read_string_attribute("command");
  relaxation.purpose = group.read_string_attribute("purpose");
  relaxation.strain = group.read_attribute<double>("strain");
  relaxation.next_history = group.read_attribute<double>("next_history");
  relaxation.next_checkpoint = group.read_attribute<std::int64_t>("next_checkpoint");
  s.steps = group.read_attribute<std::int64_t>("steps");
  const std::string stage = group.read_string_attribute("stage");
  if (stage != minimising && stage != verifying && stage != escaping)
    group.fail("attribute stage: '" + stage + "', expected minimising, verifying or escaping");
  s.verifying = stage == verifying;
  s.escaping = stage == escaping;
  // Files written before the escape existed have none under way.
  s.escaped = group.has_attribute("escaped") ? group.read_attribute<std::int64_t>("escaped") : 0;
  s.passed = group.read_attribute<std::int32_t>("passed");
  s.start_stress = group.read_attribute<double>("start_stress");
  s.verified = group.read_attribute<std::int64_t>("verified");
  s.verifying_steps = group.read_attribute<std::int64_t>("verifying_steps");
  s.windows_left = group.read_attribute<std::int32_t>("windows_left");
  if (group.has_child("fire")) {
    const h5::Group fire = group.open_group("fire");
    s.fire = protocol::FireState{
        fire.read_attribute<double>("min_step"), fire.read_attribute<double>("max_step"),
        fire.read_attribute<double>("alpha"), fire.read_attribute<std::int32_t>("downhill"),
        fire.read_attribute<std::int64_t>("stops")};
  }
  s.memory = read_memory(group.open_group("given_back"));
  return relaxation;
}

} // namespace

std::function<void(h5::File&)> relaxation_record(const protocol::Relaxation& relaxed) {
  return [held = relaxed.held_steps, verified = relaxed.verified](h5::File& file) {
    file.write_attribute<std::int64_t>("static_held_steps", held);
    file.write_attribute<std::uint8_t>("static_verified", verified ? 1 : 0);
  };
}

void write_interrupted_checkpoint(const std::string& path, const Simulation& simulation,
                                  const CheckpointLabels& labels, const h5::Provenance& provenance,
                                  const InterruptedRelaxation* relaxation) {
  // The checkpoint and its /relaxation group appear under `path` together or not at all: a file
  // without the group would resume as if no relaxation were under way.
  write_checkpoint(path, simulation, labels, provenance, [&](h5::File& file) {
    if (relaxation == nullptr) return;
    h5::Group group = file.create_group(group_name);
    write_relaxation(group, *relaxation);
  });
}

std::optional<InterruptedRelaxation> read_interrupted_relaxation(const std::string& path) {
  const h5::File file = h5::File::open(path);
  if (!file.has_child(group_name)) return std::nullopt;
  return read_relaxation(file.open_group(group_name));
}

std::string interrupted_path(const std::string& output) {
  std::filesystem::path path(output);
  const std::string extension = path.has_extension() ? path.extension().string() : std::string(".h5");
  path.replace_filename(path.stem().string() + "_interrupted" + extension);
  return path.string();
}

} // namespace aniso::dem::io
