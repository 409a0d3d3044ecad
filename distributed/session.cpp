// MPI's lifetime and its transport; without MPI, a world of one.
#include "distributed/session.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <limits>
#include <list>
#include <stdexcept>
#include <thread>

#if SB_WITH_MPI
#include <mpi.h>
#endif

namespace sb::distributed {
namespace {

/// Whether an MPI launcher started this process, and with how many ranks (0: none).
int launcher_ranks() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"}) {
        if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
    }
    if (std::getenv("PMIX_RANK") != nullptr || std::getenv("PMI_RANK") != nullptr) return 1;
    return 0;
}

#if SB_WITH_MPI

/// How long a rank sleeps between two looks at an MPI request it waits for.
constexpr std::chrono::milliseconds kPollInterval{1};

void check(int code, const char* call) {
    if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + call + " failed");
}

/// Waits for an MPI request without spinning a core: OpenMPI's blocking calls poll
/// continuously, which would take a core from the compute threads.
void wait_sleeping(MPI_Request& request) {
    for (;;) {
        int done = 0;
        check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
        if (done != 0) return;
        std::this_thread::sleep_for(kPollInterval);
    }
}

class MpiTransport : public Transport {
  public:
    MpiTransport() {
        check(MPI_Comm_dup(MPI_COMM_WORLD, &comm_), "MPI_Comm_dup");
        check(MPI_Comm_rank(comm_, &rank_), "MPI_Comm_rank");
        check(MPI_Comm_size(comm_, &size_), "MPI_Comm_size");
    }
    ~MpiTransport() override {
        try {
            while (!flush()) std::this_thread::sleep_for(kPollInterval);
        } catch (const std::exception&) {
            // A send that failed: nothing left to deliver it to.
        }
        MPI_Comm_free(&comm_);
    }
    [[nodiscard]] int rank() const override { return rank_; }
    [[nodiscard]] int size() const override { return size_; }

    void send(int destination, std::string bytes) override {
        if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
            throw std::runtime_error("MPI: a message of " + std::to_string(bytes.size()) +
                                     " bytes is too long");
        }
        // Non-blocking: two ranks sending each other long messages never wait for each other.
        pending_.push_back({std::move(bytes), MPI_REQUEST_NULL});
        Pending& p = pending_.back();
        check(MPI_Isend(p.bytes.data(), static_cast<int>(p.bytes.size()), MPI_CHAR, destination,
                        kTag, comm_, &p.request),
              "MPI_Isend");
        flush();
    }

    std::optional<Message> receive() override {
        flush();
        int arrived = 0;
        MPI_Message handle;
        MPI_Status status;
        check(MPI_Improbe(MPI_ANY_SOURCE, kTag, comm_, &arrived, &handle, &status), "MPI_Improbe");
        if (arrived == 0) return std::nullopt;
        int count = 0;
        check(MPI_Get_count(&status, MPI_CHAR, &count), "MPI_Get_count");
        Message m;
        m.source = status.MPI_SOURCE;
        m.bytes.resize(static_cast<std::size_t>(count));
        check(MPI_Mrecv(m.bytes.data(), count, MPI_CHAR, &handle, MPI_STATUS_IGNORE), "MPI_Mrecv");
        return m;
    }

    bool flush() override {
        for (auto it = pending_.begin(); it != pending_.end();) {
            int done = 0;
            check(MPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "MPI_Test");
            it = done != 0 ? pending_.erase(it) : std::next(it);
        }
        return pending_.empty();
    }

  private:
    static constexpr int kTag = 1;
    struct Pending {
        std::string bytes;
        MPI_Request request;
    };
    MPI_Comm comm_ = MPI_COMM_NULL;
    int rank_ = 0;
    int size_ = 1;
    std::list<Pending> pending_;  // stable addresses: MPI holds pointers into them
};

#endif

}  // namespace

Session::Session() {
    const int launched = launcher_ranks();
#if SB_WITH_MPI
    if (launched > 0) {
        int provided = 0;
        check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
        initialised_ = true;
        if (provided < MPI_THREAD_FUNNELED) {
            throw std::runtime_error(
                "MPI: this MPI library cannot run threads beside MPI (MPI_THREAD_FUNNELED)");
        }
        transport_ = std::make_unique<MpiTransport>();
        rank_ = transport_->rank();
        size_ = transport_->size();
        if (size_ == 1) transport_.reset();  // alone: nothing to exchange
    }
#else
    if (launched > 1) {
        throw std::runtime_error(
            "started as " + std::to_string(launched) +
            " MPI processes, but this shakerbench was built without MPI: each would run the "
            "whole campaign. Build with -DSB_WITH_MPI=ON (docs/cluster.md), or run one process.");
    }
#endif
}

Session::~Session() {
#if SB_WITH_MPI
    if (!initialised_) return;
    transport_.reset();
    // Every rank waits here for the others (rank 0 writes the output meanwhile), sleeping.
    MPI_Request barrier = MPI_REQUEST_NULL;
    if (MPI_Ibarrier(MPI_COMM_WORLD, &barrier) == MPI_SUCCESS) {
        try {
            wait_sleeping(barrier);
        } catch (const std::exception&) {
        }
    }
    MPI_Finalize();
#endif
}

std::string Session::describe() const {
    char host[256] = {};
    if (gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
    return "rank " + std::to_string(rank_) + " of " + std::to_string(size_) + ": pid " +
           std::to_string(getpid()) + " on " + host;
}

void Session::abort(int exit_code) {
#if SB_WITH_MPI
    if (initialised_) MPI_Abort(MPI_COMM_WORLD, exit_code);
#endif
    std::exit(exit_code);
}

bool Session::built_with_mpi() {
#if SB_WITH_MPI
    return true;
#else
    return false;
#endif
}

}  // namespace sb::distributed
