// The mapper's processes under MPI: their agreement before each frame, and
// the compositing of the texture after it (vtkIBFVSMapper.cxx).
#include "IBFVSRanks.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ibfvs/core/image/composite.h"
#include "ibfvs/core/mesh/mesh.h"
#include "ibfvs/core/mesh/mesh_bytes.h"
#include "ibfvs/gl/objects.h"
#include "ibfvs/render/session.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

namespace ibfvs::paraview {
namespace {

// The agreement as one reduction (a maximum): flags as 0 or 1, the speed,
// the bounds' lower corner negated (the maximum of the negation is the
// minimum); no bounds as the lowest value.
enum Slot {
  kBad,
  kRestart,
  kResize,
  kChanged,
  kMoved,
  kSpeed,
  kMinX,
  kMaxX = kMinX + 3,
  kSize = kMaxX + 3
};
constexpr double kNone = -1e300;

}  // namespace

Agreement agree(const Agreement& mine, vtkMultiProcessController* controller) {
  double slots[kSize];
  const ibfvs::HostChanges& c = mine.changes;
  const bool flags[] = {mine.bad, c.restart, c.resize, c.changed, c.moved};
  for (int k = 0; k < kSpeed; ++k) slots[k] = flags[k] ? 1.0 : 0.0;
  slots[kSpeed] = c.speed;
  for (int k = 0; k < 3; ++k) {
    slots[kMinX + k] = c.bounds ? -static_cast<double>(c.bounds->first[k]) : kNone;
    slots[kMaxX + k] = c.bounds ? static_cast<double>(c.bounds->second[k]) : kNone;
  }
  if (controller && controller->GetNumberOfProcesses() > 1) {
    double all[kSize];
    controller->AllReduce(slots, all, kSize, vtkCommunicator::MAX_OP);
    std::copy(all, all + kSize, slots);
  }
  Agreement out;
  ibfvs::HostChanges& all = out.changes;
  bool* const out_flags[] = {&out.bad, &all.restart, &all.resize, &all.changed, &all.moved};
  for (int k = 0; k < kSpeed; ++k) *out_flags[k] = slots[k] > 0.0;
  all.speed = static_cast<float>(slots[kSpeed]);
  if (slots[kMaxX] > kNone) {
    glm::vec3 lower, upper;
    for (int k = 0; k < 3; ++k) {
      lower[k] = static_cast<float>(-slots[kMinX + k]);
      upper[k] = static_cast<float>(slots[kMaxX + k]);
    }
    all.bounds = {lower, upper};
  }
  return out;
}

void composite_frame(vtkMultiProcessController* controller, ibfvs::Session* session, int width,
                     int height) {
  const ibfvs::gl::SavedState saved;  // the reads bind the library's framebuffers
  const int w = width, h = height;
  // The statistics where any process's renderer left them due (its frame
  // plan: pass_runs), F composited for them by all alike.
  int due = session && session->statistics_due() ? 1 : 0, any = 0;
  controller->AllReduce(&due, &any, 1, vtkCommunicator::MAX_OP);
  const bool statistics = any > 0;
  ibfvs::ImageF depth = session ? session->read_depth() : ibfvs::ImageF(w, h, 1, 1.0f);
  ibfvs::ImageF texture = session ? session->read_texture_raw()
                                  : ibfvs::ImageF(w, h, ibfvs::IbfvsRenderer::kRawChannels, 0.0f);
  ibfvs::ImageF output;
  std::vector<ibfvs::ImageF*> images{&texture};
  if (statistics) {
    output = session ? session->read_output_raw() : ibfvs::ImageF(w, h, 4, 0.0f);
    images.push_back(&output);
  }
  ibfvs::CompositeGroup group;
  group.rank = controller->GetLocalProcessId();
  group.size = controller->GetNumberOfProcesses();
  group.min_all = [controller](std::span<std::uint64_t> values) {
    std::vector<unsigned long> send(values.begin(), values.end());
    controller->AllReduce(send.data(), reinterpret_cast<unsigned long*>(values.data()),
                          static_cast<vtkIdType>(values.size()), vtkCommunicator::MIN_OP);
  };
  group.sum_all = [controller](std::span<float> values) {
    std::vector<float> send(values.begin(), values.end());
    controller->AllReduce(send.data(), values.data(), static_cast<vtkIdType>(values.size()),
                          vtkCommunicator::SUM_OP);
  };
  ibfvs::composite_nearest(images, depth, group);
  if (session) session->take_composited(texture, statistics ? &output : nullptr);
}

ibfvs::TriMesh gather_pieces(vtkMultiProcessController* controller, const ibfvs::TriMesh* mine) {
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  if (ranks <= 1) return mine ? *mine : ibfvs::TriMesh{};
  ibfvs::ByteWriter writer;
  ibfvs::put_mesh(writer, mine ? *mine : ibfvs::TriMesh{});
  const std::string bytes = writer.take();
  const long length = static_cast<long>(bytes.size());
  std::vector<long> lengths(static_cast<std::size_t>(ranks), 0);
  controller->Gather(&length, lengths.data(), 1, 0);
  const bool root = controller->GetLocalProcessId() == 0;
  std::vector<vtkIdType> counts(lengths.begin(), lengths.end()), offsets(counts.size(), 0);
  vtkIdType total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = total;
    total += counts[r];
  }
  std::string all(root ? static_cast<std::size_t>(total) : 0, '\0');
  controller->GatherV(bytes.data(), all.data(), length, counts.data(), offsets.data(), 0);
  ibfvs::TriMesh whole;
  if (!root) return whole;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    ibfvs::ByteReader reader(std::string_view(all).substr(static_cast<std::size_t>(offsets[r]),
                                                          static_cast<std::size_t>(counts[r])),
                             "process " + std::to_string(r) + "'s piece");
    const ibfvs::TriMesh piece = ibfvs::get_mesh(reader);
    if (piece.vertex_count() > 0) ibfvs::append_mesh(whole, piece);
  }
  return whole;
}

}  // namespace ibfvs::paraview
