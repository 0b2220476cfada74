// disco — the search's Transport (search/transport.h) over MPI: MPI_COMM_WORLD, one tag
// per MessageKind, bodies as MPI_CHAR arrays. Construct it between MPI_Init_thread and
// MPI_Finalize (mpi/disco_main.cpp), on every rank (the constructor is collective).
#pragma once

#include "search/transport.h"

namespace disco {

class MpiTransport : public Transport {
 public:
  MpiTransport();
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int ranks_on_this_host() const override { return host_ranks_; }
  void send(int to, MessageKind kind, const std::string& body) override;
  std::optional<Message> poll() override;
  Message receive() override;

 private:
  int rank_ = 0, size_ = 1, host_ranks_ = 1;
};

}  // namespace disco
