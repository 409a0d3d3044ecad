// The processes of a run: MPI's world when an MPI launcher (mpirun, srun) started this
// process in a build with MPI (SB_WITH_MPI), else this process alone.
#pragma once

#include <memory>
#include <string>

#include "distributed/transport.hpp"

namespace sb::distributed {

/// Initialises MPI at construction when the process was started by an MPI launcher, and
/// finalises it at destruction once every rank got there (waiting without spinning). Create
/// one, on the thread that makes every MPI call (the ranks' other threads never do).
class Session {
  public:
    /// Throws std::runtime_error when an MPI launcher started several processes of a build
    /// without MPI (each would run the whole campaign), or MPI cannot start.
    Session();
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    [[nodiscard]] int rank() const { return rank_; }
    [[nodiscard]] int size() const { return size_; }
    /// The exchange between the ranks; null when this process is alone.
    [[nodiscard]] Transport* transport() { return transport_.get(); }
    /// "rank 1 of 2: pid 4242 on node17"
    [[nodiscard]] std::string describe() const;
    /// Ends every rank of the run at once with `exit_code` (a rank that cannot go on while
    /// others wait for it); alone, exits.
    [[noreturn]] void abort(int exit_code);

    /// Whether this build can run on several processes.
    static bool built_with_mpi();

  private:
    int rank_ = 0;
    int size_ = 1;
    /// MPI_Init ran here (read only by a build with MPI; `[[maybe_unused]]` for the other,
    /// whose unity build sees every member function and finds no reader).
    [[maybe_unused]] bool initialised_ = false;
    std::unique_ptr<Transport> transport_;
};

}  // namespace sb::distributed
