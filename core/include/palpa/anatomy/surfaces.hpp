#pragma once
// The two surfaces of a body on its support, taken from what the user holds
// (docs/anatomy-import.md): a label volume, a skin mesh with a support mesh, or one closed
// mesh on a support plane. Each refuses, in one line naming where, a body whose free
// surface is not a height field over its support (an overhang).
#include <string>
#include <vector>

#include "palpa/anatomy/height_field.hpp"
#include "palpa/anatomy/label_table.hpp"
#include "palpa/anatomy/label_volume.hpp"
#include "palpa/anatomy/triangle_mesh.hpp"

namespace palpa::anatomy {

/// The support's frame and both surfaces from a label volume: the plane of least squares
/// through the support's boundary with the soft labels, n towards the tissue; the support
/// bends away from it when a quadric over the plane fits its boundary twice as well
/// ("curved"). `source` names the file in errors.
SurfacePair surfaces_from_volume(const LabelVolume& volume, const LabelTable& table, const std::string& source);

/// A skin surface (open) lying on a support surface (open).
SurfacePair surfaces_from_meshes(const TriangleMesh& skin, const TriangleMesh& support, const std::string& skin_source,
                                 const std::string& support_source);

/// One closed surface whose underside lies on the plane normal . x + offset = 0 (normal
/// need not be unit; x in m); the normal is turned to point into the body if needed.
SurfacePair surfaces_from_closed_mesh(const TriangleMesh& mesh, const Vec3& normal, double offset,
                                      const std::string& source);

/// Millimetres for people: "(x, y, z) mm" of a world point (m).
std::string millimetres(const Vec3& p);

}  // namespace palpa::anatomy
