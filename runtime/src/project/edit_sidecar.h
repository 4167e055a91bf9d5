// Private: the edited-heights sidecar of a saved project (docs/project-format.md, "Edited heights").
//
// Incremental edits depend on their order (s5.3 coherence), so re-synthesizing a project's saved
// constraints from scratch does not give what the designer saw. Saving writes, beside the .tsyn, what
// the session had: the extent's synthesized heights (before the layer stack, which is re-applied on
// opening: it is deterministic), the frozen mask, the synthesis history (so editing can continue
// exactly), the point and curve lifts, and the reference the world outside the extent is synthesized from. A
// digest of everything the heights depend on decides whether the file still belongs to its project.
//
// Layout (little-endian): "TSYNEDIT", u32 version, u64 header bytes, header JSON, the blobs the
// header lists in order, u64 FNV-1a of everything before it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "terrasynth/constraints.h"
#include "terrasynth/project.h"

namespace terrasynth::project {

// What a project does not hold of its constraints but their synthesis depends on: the lifts.
struct ConstraintLifts {
    std::vector<float> points;                // lift_m of each point, in order
    std::vector<std::array<float, 2>> tilts;  // tilt_east, tilt_south of each point (empty: none)
    std::vector<std::array<float, 2>> wide_tilts;  // wide_tilt_east, wide_tilt_south likewise
    std::vector<std::vector<float>> curves;   // lift profile of each curve (empty: none)
};
ConstraintLifts liftsOf(const SynthesisConstraints* constraints);
// Gives the points and curves these lifts; false (nothing changed) when they are for others.
bool applyLifts(const ConstraintLifts& lifts, std::vector<PointConstraint>& points, std::vector<CurveConstraint>& curves);

struct EditSidecar {
    static constexpr uint32_t kVersion = 1;
    uint64_t digest = 0;
    PixelWindow extent;
    std::vector<float> heights;         // synthesized extent before the layer stack, row-major
    std::vector<uint8_t> frozen;        // 1 = frozen (freeze brush and pastes)
    SynthesisHistory history;           // empty levels when not stored or not read
    ConstraintLifts lifts;              // of the project's points and curves, in order
    ConstraintsJson reference;          // constraints the world outside the extent is synthesized with
    ConstraintLifts reference_lifts;
};

constexpr char kEditSidecarMagic[8] = {'T', 'S', 'Y', 'N', 'E', 'D', 'I', 'T'};

std::string encodeEditSidecar(const EditSidecar& sidecar);
// The file validated whole (edit_sidecar_read.cpp): the header parsed with bounded depth and read
// field by field, blob sizes, finite heights and history offsets within limits::kMaxAbsHeightM, a
// 0/1 frozen mask, lifts in range. Errors read "<path>: <field>: <problem>". History atlas indices
// need the database: IncrementalTerrain::restore checks them. `with_history` false skips the
// history (what Terrain needs).
Result<EditSidecar> decodeEditSidecar(const std::string& bytes, const std::string& path, bool with_history);
// Only the digest (cheap check before decoding everything); the header is still bounded and the
// digest must be 16 hex digits.
Result<uint64_t> sidecarDigest(const std::string& bytes, const std::string& path);

// What edited heights depend on: the database, the extent, the synthesis settings, the constraints
// (canonical: as constraintsToJson writes them, masks included) and the layer stack (canonical JSON).
uint64_t editDigest(const Project& project, const ExemplarDatabase& db, const ConstraintsJson& canonical_constraints,
                    const std::string& canonical_layers);
// The canonical digest of a project as it is on disk (parses constraints and layers). Errors: theirs.
Result<uint64_t> projectEditDigest(const Project& project, const ExemplarDatabase& db);

}  // namespace terrasynth::project
