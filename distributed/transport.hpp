// How the ranks of a distributed run exchange messages: addressed byte strings, delivered in
// the order sent between any two ranks, never waiting. MPI's in an MPI build (mpi_transport),
// an in-process one for tests.
#pragma once

#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace sb::distributed {

struct Message {
    int source = 0;     ///< rank that sent it
    std::string bytes;  ///< as sent
};

/// One rank's end of the message exchange, used by one thread of that rank.
class Transport {
  public:
    virtual ~Transport() = default;
    [[nodiscard]] virtual int rank() const = 0;
    [[nodiscard]] virtual int size() const = 0;
    /// Sends `bytes` to rank `destination` and returns at once (the transport keeps them until
    /// they are delivered).
    virtual void send(int destination, std::string bytes) = 0;
    /// A message that has arrived from any rank, if one has; never waits.
    virtual std::optional<Message> receive() = 0;
    /// Advances the sends under way; true when every one has been delivered.
    virtual bool flush() = 0;
};

/// Every rank in this process, each a mailbox: to test the protocols above the transport with
/// several ranks on threads.
class InProcessNetwork {
  public:
    explicit InProcessNetwork(int ranks);
    /// Rank r's end; the network must outlive it.
    std::unique_ptr<Transport> endpoint(int rank);

  private:
    friend class InProcessTransport;
    struct Mailbox {
        std::mutex mutex;
        std::deque<Message> messages;
    };
    std::vector<std::unique_ptr<Mailbox>> mailboxes_;
};

}  // namespace sb::distributed
