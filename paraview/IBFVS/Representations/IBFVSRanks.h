// The mapper's processes under MPI (VTK's global controller): their
// agreement before each frame, so that all draw the texture or none and all
// take a change alike (their frame counters and noise stay equal), and the
// compositing of the texture after each frame, by nearest depth
// (ibfvs/core/image/composite.h).
#ifndef IBFVSRanks_h
#define IBFVSRanks_h

#include "ibfvs/render/host_flow.h"

class vtkMultiProcessController;

namespace ibfvs {
class Session;
struct TriMesh;
}  // namespace ibfvs

namespace ibfvs::paraview {

/// What a process says before a frame: whether its piece cannot be drawn
/// with the texture, and what its flow owes (HostFlow::pending); agree()
/// gives every process the same.
struct Agreement {
  bool bad = false;  ///< a piece cannot be drawn with the texture: all draw plain
  ibfvs::HostChanges changes;
};

/// Every process's agreement: any flag of any process, the fastest vector
/// and the bounds of all pieces. One collective; without a controller, or
/// alone, `mine`.
Agreement agree(const Agreement& mine, vtkMultiProcessController* controller);

/// After a frame: F_t (and F, where the contrast statistics are due in any
/// process's renderer: its frame plan, pass_runs) composited by nearest
/// depth across the processes, written back, and the statistics run on the
/// composite. `session` is null for an empty piece, which takes part with
/// empty images of width x height. Collective.
void composite_frame(vtkMultiProcessController* controller, ibfvs::Session* session, int width,
                     int height);

/// Every process's piece (null: an empty one) as one mesh on process 0, in
/// the processes' order (ibfvs::append_mesh); the others get an empty mesh.
/// A page of the whole surface under MPI. Collective.
ibfvs::TriMesh gather_pieces(vtkMultiProcessController* controller, const ibfvs::TriMesh* mine);

}  // namespace ibfvs::paraview

#endif
