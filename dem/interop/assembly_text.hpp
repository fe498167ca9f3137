#pragma once
// Assemblies in the text formats of other DEM codes: LAMMPS / LIGGGHTS data files
// (`read_data`, `atom_style sphere` or `granular`) and YADE's text export of spheres
// (`yade.export.text`, "x y z r" lines) and DEMPLA/OVAL start files ("D-files" of spheres or
// ovoids, Kuhn's code: github.com/mrkuhn53/dempla, octave/Read_D_file3.m). The way in and out for `aniso-dem
// import` and `aniso-dem export` (docs/user-guide.md, "Bringing a packing from another code").

#include "common/h5/checkpoint.hpp"
#include "common/tensor.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace aniso::dem::interop {

/// Particles as another code stores them: ids as given, positions relative to the box's lower
/// corner (not yet wrapped), one row per particle. Spheres, or ovoids of one aspect ratio and
/// splice angle (DEMPLA's D-files).
struct ImportedAssembly {
  std::string source; ///< the file read
  std::string format; ///< "lammps", "yade" or "dempla"
  Vec3 lengths = Vec3::Zero();
  std::vector<std::uint64_t> id;
  std::vector<double> diameter;       ///< [m]
  std::vector<double> density;        ///< [kg/m^3]; empty when the file has none (YADE)
  std::vector<Vec3> position;         ///< [m], relative to the lower corner of the box
  std::vector<Vec3> velocity;         ///< [m/s]; zero when the file has none
  std::vector<Vec3> angular_velocity; ///< [rad/s]; zero when the file has none
  double aspect_ratio = 1.0;          ///< axial height / mid-plane diameter of every particle; 1 = spheres
  double splice_angle = 0;            ///< ovoids: the splice angle beta [rad]
  std::vector<Vec3> axis;             ///< ovoids: unit axis of revolution of each particle; empty for spheres

  [[nodiscard]] std::size_t size() const { return id.size(); }
};

/// Reads a LAMMPS data file of spheres: header counts and an orthogonal box, an Atoms section
/// with `id type diameter density x y z [ix iy iz]` rows, an optional Velocities section
/// (`id vx vy vz wx wy wz`). Refuses by name what aniso cannot represent (a tilted box, another
/// atom style, bonds, point particles, duplicate or missing ids) with FileError naming the file
/// and line.
ImportedAssembly read_lammps_data(const std::string& path);

/// Reads YADE's text export of spheres ("x y z r" per line, '#' comments) in a periodic cell
/// of the given lengths (YADE's text export does not carry the cell); ids are 1..N in file order.
ImportedAssembly read_yade_text(const std::string& path, const Vec3& lengths);

/// Reads a DEMPLA (OVAL) D-file of spheres or ovoids: the shape code (4 spheres, 5 ovoids); the
/// particle count and the cell's lengths; the cell's three shear offsets (must be 0: aniso's cell
/// is rectangular); for ovoids the splice angle in degrees; then per sphere "radius x1 x2 x3", per
/// ovoid "half-width aspect x1 x2 x3 gamma1 gamma2" (axis angles in degrees, axis = (sin g1 cos g2,
/// sin g1 sin g2, cos g1); a row may run over several lines, as Fortran's list-directed read
/// allows). Ids are 1..N in file order. DEMPLA has no units: its sample files are scaled to
/// D50 = 1 (give import --d50 to make them metres). Ovoids of several aspect ratios (aniso holds
/// one per assembly) and the other shapes are refused by name.
ImportedAssembly read_dempla_dfile(const std::string& path);

/// Writes a whole checkpoint as a DEMPLA D-file (shape 4 for spheres, 5 for ovoids with the
/// splice angle and each axis as DEMPLA's two angles; lengths in metres, positions wrapped into
/// [0, L)), the start file of a DEMPLA run on the same assembly. InputError if the particles
/// have several aspect ratios.
void write_dempla_dfile(const std::string& path, const h5::Checkpoint& checkpoint);

/// The diameter below which half the solid volume lies (the paper's D50, by volume).
double median_by_volume(std::vector<double> diameters);

/// The assembly with every length (cell, positions, diameters, velocities) multiplied so that
/// its median diameter by volume is `d50`.
ImportedAssembly scaled_to_d50(ImportedAssembly assembly, double d50);

/// Writes a whole checkpoint of spheres (every row) as a LAMMPS data file (`atom_style sphere`,
/// box [0, L), one atom type), with its Velocities. The LAMMPS id of a particle is its
/// /particles/source_id where the checkpoint has one (an imported assembly), else id + 1.
/// InputError if a particle is not a sphere.
void write_lammps_data(const std::string& path, const h5::Checkpoint& checkpoint);

/// The whitespace-separated words of a line of text.
std::vector<std::string> split_words(const std::string& text);

/// The LAMMPS id write_lammps_data gives each particle row.
std::vector<std::uint64_t> lammps_ids(const h5::Checkpoint& checkpoint);

} // namespace aniso::dem::interop
