#include "mpi/mpi_transport.h"

#include <mpi.h>

namespace disco {
namespace {

constexpr int kTag[] = {1, 2, 3, 4, 5};  // by MessageKind: kResult, kTask, kStop, kIncumbent, kProgress
constexpr int kKinds = sizeof kTag / sizeof kTag[0];

int tag_of(MessageKind kind) { return kTag[static_cast<int>(kind)]; }
MessageKind kind_of(int tag) {
  for (int k = 0; k < kKinds; ++k)
    if (kTag[k] == tag) return static_cast<MessageKind>(k);
  return MessageKind::kStop;
}

// Receives the message `probe` found.
Message receive_probed(const MPI_Status& probe) {
  int n = 0;
  MPI_Get_count(&probe, MPI_CHAR, &n);
  Message m;
  m.kind = kind_of(probe.MPI_TAG);
  m.source = probe.MPI_SOURCE;
  m.body.assign(static_cast<std::size_t>(n), '\0');
  MPI_Status status;
  MPI_Recv(m.body.data(), n, MPI_CHAR, probe.MPI_SOURCE, probe.MPI_TAG, MPI_COMM_WORLD, &status);
  return m;
}

}  // namespace

MpiTransport::MpiTransport() {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm host;  // the ranks that share this rank's memory (a collective call: every rank)
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host);
  MPI_Comm_size(host, &host_ranks_);
  MPI_Comm_free(&host);
}

void MpiTransport::send(int to, MessageKind kind, const std::string& body) {
  MPI_Send(body.data(), static_cast<int>(body.size()), MPI_CHAR, to, tag_of(kind), MPI_COMM_WORLD);
}

std::optional<Message> MpiTransport::poll() {
  int ready = 0;
  MPI_Status probe;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &ready, &probe);
  if (!ready) return std::nullopt;
  return receive_probed(probe);
}

Message MpiTransport::receive() {
  MPI_Status probe;
  MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &probe);
  return receive_probed(probe);
}

}  // namespace disco
