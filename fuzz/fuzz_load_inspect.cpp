// libFuzzer harness: the whole input path of `offsetopt check` and `offsetopt inspect` on
// arbitrary bytes. The format is recognised by content as for a file without an extension
// (read_raw_mesh_from_memory), with OBJ as the fallback, so any seed file works unchanged.
//   read -> validate_mesh + every defect line (check) -> load_raw_mesh, default and strict
//   -> volume integrals, mass properties, principal inertia, area, stability (inspect).
// Besides fuzz_support.h's assertions: a mesh load_mesh accepts validates clean (several
// components aside), encloses a positive volume, and every number inspect reports is finite.
#include <cmath>

#include "fuzz/fuzz_support.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "mass/surface_area.h"
#include "mass/volume_integrals.h"
#include "meshio/load_mesh.h"
#include "meshio/read_raw_mesh.h"
#include "meshio/validate_mesh.h"

namespace {

using namespace offsetopt;
using offsetopt::fuzz::check_error_message;

const std::string kName = "input";

void check_finite(double value, const char* what) {
  OFFSETOPT_FUZZ_CHECK(std::isfinite(value), std::string(what) + " is not finite");
}

RawMesh read_any(const std::string& bytes) {
  try {
    return read_raw_mesh_from_memory(kName, bytes);
  } catch (const MeshInputError& e) {
    if (std::string(e.what()).find("unrecognised mesh format") == std::string::npos) throw;
  }
  return read_raw_mesh_from_memory(kName + ".obj", bytes);
}

// What `check` prints: a line per defect.
void check_command(const RawMesh& raw) {
  const MeshValidation validation = validate_mesh(Mesh{raw.V, raw.F});
  const DefectSource source{nullptr, nullptr, &raw.face_line, &raw.vertex_line};
  for (const Defect& defect : validation.defects) check_error_message(kName, defect_report_line(kName, defect, source).c_str());
  if (validation.valid()) {
    OFFSETOPT_FUZZ_CHECK(validation.volume_computed && validation.volume > 0, "a valid mesh has a positive volume");
    OFFSETOPT_FUZZ_CHECK(validation.components == 1, "a valid mesh is one component");
  }
}

// What `inspect` computes after load_mesh.
void inspect_command(const LoadedMesh& loaded) {
  const Mesh& mesh = loaded.mesh;
  const MeshValidation validation = validate_mesh(mesh);
  for (const Defect& d : validation.defects)
    OFFSETOPT_FUZZ_CHECK(d.kind == DefectKind::several_components,
                         "load_raw_mesh accepted a mesh with defect: " + defect_report_line(kName, d));
  OFFSETOPT_FUZZ_CHECK(validation.volume > 0, "load_raw_mesh accepted a mesh of volume <= 0");
  OFFSETOPT_FUZZ_CHECK(validation.unreferenced_vertices == 0, "load_raw_mesh kept unreferenced vertices");

  const VolumeIntegrals integrals = volume_integrals(mesh);
  const double volume = integrals.values(kIntVolume);
  if (!(volume > 0.0) || !std::isfinite(volume)) return;  // inspect refuses this with a message
  const Vector10d P = mass_properties(integrals);
  for (int k = 0; k < 10; ++k) check_finite(P(k), "a mass property");
  const PrincipalInertia principal = principal_inertia(P);
  for (int k = 0; k < 3; ++k) check_finite(principal.moments(k), "a principal moment");
  for (int k = 0; k < 9; ++k) check_finite(principal.axes(k), "a principal axis component");
  check_finite(surface_area(mesh), "the area");
  const Stability stability = compute_stability(mesh, P.segment<3>(kCx));
  OFFSETOPT_FUZZ_CHECK(!stability.support_polygon.empty(), "empty support polygon");
  OFFSETOPT_FUZZ_CHECK(stability.contact_vertex_count >= 1, "no contact vertex");
  check_finite(stability.ground_tol, "the ground tolerance");
  check_finite(stability.com_margin, "the com margin");
  check_finite(stability.tipping_angle_deg, "the tipping angle");
}

void load_and_inspect(const RawMesh& raw, const LoadOptions& options) {
  LoadedMesh loaded;
  try {
    loaded = load_raw_mesh(kName, raw, options);
  } catch (const MeshInputError& e) {
    check_error_message(kName, e.what());
    return;
  }
  for (const std::string& warning : loaded.warnings) check_error_message("", warning.c_str());
  inspect_command(loaded);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  // 3MF (by content: a zip) counts the bytes it may inflate to as input (fuzz_support.h).
  const std::size_t inflatable = offsetopt::fuzz::inflatable_bytes(data, size);
  offsetopt::fuzz::HeapBudget budget(size, offsetopt::fuzz::kBytesPerInputByte * (size + inflatable) + offsetopt::fuzz::kFixedBytes);
  RawMesh raw;
  try {
    raw = read_any(bytes);
  } catch (const MeshInputError& e) {
    check_error_message(kName, e.what());
    return 0;
  }
  offsetopt::fuzz::check_raw_mesh(raw, offsetopt::fuzz::is_text_format(raw.format));
  check_command(raw);
  LoadOptions strict;
  strict.flip_inside_out = false;
  strict.single_component = true;
  load_and_inspect(raw, strict);
  load_and_inspect(raw, LoadOptions{});
  return 0;
}
