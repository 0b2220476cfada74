// disco — how the ranks of a search talk: the interface the search (search/run_search.h)
// is written against, and that mpi/mpi_transport.h implements with MPI.
//
// The search has one coordinator, rank 0, and workers, ranks 1..size-1. Messages are
// text (JSON made by the search); the transport only carries them:
//   worker -> rank 0   kResult: a finished task's outcome (the body of the first one is "{}":
//                      a worker's first request for work);
//                      kProgress: a new best within the task it runs (shared incumbent);
//   rank 0 -> worker   kTask: a task to run; kStop: no more tasks, the worker returns;
//                      kIncumbent: a better best of the scene of the task it runs.
// Messages from one rank to another arrive in the order they were sent.
// Workers call the transport only between solves (MUMPS inside Ipopt exports a fake MPI;
// see mpi/CMakeLists.txt), and on rank 0 only the coordinator thread calls it while rank
// 0's own worker solves (MPI_THREAD_SERIALIZED).
#pragma once

#include <optional>
#include <string>

namespace disco {

enum class MessageKind { kResult, kTask, kStop, kIncumbent, kProgress };

struct Message {
  MessageKind kind = MessageKind::kResult;
  int source = 0;  // the sending rank
  std::string body;
};

class Transport {
 public:
  virtual ~Transport() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // How many ranks of the search run on this rank's machine (they share its memory:
  // model.memory_limit, core/model/model_size.h).
  virtual int ranks_on_this_host() const = 0;
  // Sends `kind` with `body` to rank `to`.
  virtual void send(int to, MessageKind kind, const std::string& body) = 0;
  // A message to this rank, if one has arrived (rank 0: from any worker; a worker: from
  // rank 0); never blocks.
  virtual std::optional<Message> poll() = 0;
  // A worker: the next message from rank 0; blocks until it arrives.
  virtual Message receive() = 0;
};

}  // namespace disco
