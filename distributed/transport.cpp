// The in-process transport.
#include "distributed/transport.hpp"

#include <stdexcept>

namespace sb::distributed {

class InProcessTransport : public Transport {
  public:
    InProcessTransport(InProcessNetwork& network, int rank) : network_(network), rank_(rank) {}
    [[nodiscard]] int rank() const override { return rank_; }
    [[nodiscard]] int size() const override { return static_cast<int>(network_.mailboxes_.size()); }
    void send(int destination, std::string bytes) override {
        auto& box = *network_.mailboxes_.at(static_cast<std::size_t>(destination));
        std::lock_guard<std::mutex> lock(box.mutex);
        box.messages.push_back({rank_, std::move(bytes)});
    }
    std::optional<Message> receive() override {
        auto& box = *network_.mailboxes_[static_cast<std::size_t>(rank_)];
        std::lock_guard<std::mutex> lock(box.mutex);
        if (box.messages.empty()) return std::nullopt;
        Message m = std::move(box.messages.front());
        box.messages.pop_front();
        return m;
    }
    bool flush() override { return true; }

  private:
    InProcessNetwork& network_;
    int rank_;
};

InProcessNetwork::InProcessNetwork(int ranks) {
    if (ranks < 1) throw std::invalid_argument("InProcessNetwork: ranks must be >= 1");
    for (int r = 0; r < ranks; ++r) mailboxes_.push_back(std::make_unique<Mailbox>());
}

std::unique_ptr<Transport> InProcessNetwork::endpoint(int rank) {
    if (rank < 0 || rank >= static_cast<int>(mailboxes_.size())) {
        throw std::out_of_range("InProcessNetwork: no rank " + std::to_string(rank));
    }
    return std::make_unique<InProcessTransport>(*this, rank);
}

}  // namespace sb::distributed
