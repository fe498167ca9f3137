#include "fabric/config.hpp"

#include "common/units.hpp"

namespace aniso::fabric {

FabricConfig read_fabric_config(config::Reader& reader) {
  FabricConfig c;
  c.output_dir = reader.text("fabric.output_dir", c.output_dir,
                             "folder for the results (fabric.h5 or fabric_series.h5, with CSV beside)");
  c.rattler_min_contacts = reader.integer(
      "fabric.rattler_min_contacts", c.rattler_min_contacts, config::Range::closed(1, 12),
      "a particle with fewer contacts is a rattler; removing one can make its partners rattlers too");
  c.strong_factor =
      reader.real("fabric.strong_factor", c.strong_factor, units::none, config::Range::positive(),
                  "strong contacts carry a normal force above this multiple of the mean "
                  "(paper: 1, eq. (Fcstrong))");
  return c;
}

} // namespace aniso::fabric
