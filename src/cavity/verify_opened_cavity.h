// The solid with its openings (cavity/open_cavity.h) verified as it will be written: the cut solid
// rounded to the output's precision (cavity/round_for_output.h, the cut solid as one surface), then
//   - one closed, oriented 2-manifold (each directed edge once, its opposite once, on positions as
//     a reader merges them), up to the unmatched edges the uncut solid had (an input's own pinch);
//   - no face pair meeting by the exact rule (geometry/intersecting_faces.h) where either face is
//     new to the cut (re-triangulated or on a prism); the faces copied unchanged were verified with
//     the cavity before the cut, the input's own pairs included;
//   - no defect the rounding made and could not undo;
//   - the goal on the cut solid: the void is the outer surface less the solid (cavity, holes and
//     channel), and for stand-filled with a channel the liquid fills that void up to the channel's
//     spill height (cut by a plane, cavity/open_cavity.h cut_by_plane); drain holes are taken as
//     plugged when filled.
// The walls are those of the cavity verified before the cut (`uncut`): the cut only removes
// material, and the channel's and holes' own surfaces are exempt.
#pragma once
#include <optional>

#include "cavity/open_cavity.h"
#include "cavity/verify_offsets.h"

namespace offsetopt {

struct VerifiedOpenedCavity {
  OpenedCavity opened;              // as cut, before rounding
  Mesh solid;                       // as written
  Mesh void_surfaces;               // outer surface + the solid reversed: its integrals are the void's
  std::optional<Mesh> liquid;       // stand-filled with a channel: outer + solid below the spill height
  double void_volume = 0.0, liquid_volume = 0.0;
  bool closed = false;
  long long new_pairs = 0;          // with a face new to the cut (at most the search's cap)
  long long rounding_new_pairs = 0;
  Verification verification;
};

// `outer` and `cavity` as verified (rounded) in `uncut`, which must be valid; `input` carries the
// goal and tolerances (its outer, inner, liquid and goal_only are replaced).
VerifiedOpenedCavity verify_opened_cavity(const Mesh& outer, const Mesh& cavity, const OpenCavityOptions& options,
                                          VerifyInput input, const Verification& uncut, StoredPrecision precision);

}  // namespace offsetopt
