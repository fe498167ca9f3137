// FixedExchange, the per-step ghost refresh's transport: every rank gets exactly what each
// partner wrote for it, in place, again and again with the same buffers (runs on 1, 2 and 3
// ranks; on one rank there is nobody to talk to and nothing moves).
#include "common/exchange.hpp"
#include "common/mpi.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace {

using aniso::mpi::Comm;

// How many doubles rank `from` sends to rank `to` (uneven, and none between some pairs).
std::size_t count(int from, int to) {
  return from == to ? 0 : static_cast<std::size_t>((from * 7 + to * 3) % 5);
}

double value(int from, int to, std::size_t k, int round) {
  return 1e6 * round + 1e4 * from + 1e2 * to + static_cast<double>(k) + 0.25;
}

TEST(FixedExchange, DeliversWhatEachPartnerWroteEveryRound) {
  const Comm comm = Comm::world();
  const int me = comm.rank(), n = comm.size();
  std::vector<std::size_t> sends(static_cast<std::size_t>(n)), receives(static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r) {
    sends[static_cast<std::size_t>(r)] = count(me, r);
    receives[static_cast<std::size_t>(r)] = count(r, me);
  }
  aniso::FixedExchange exchange;
  exchange.resize(comm, sends, receives);
  for (int round = 0; round < 3; ++round) {
    for (int r = 0; r < n; ++r) {
      const auto out = exchange.outgoing(r);
      ASSERT_EQ(out.size(), count(me, r));
      for (std::size_t k = 0; k < out.size(); ++k)
        out[k] = value(me, r, k, round);
    }
    exchange.exchange(comm);
    for (int r = 0; r < n; ++r) {
      const auto in = exchange.incoming(r);
      ASSERT_EQ(in.size(), count(r, me));
      for (std::size_t k = 0; k < in.size(); ++k)
        EXPECT_EQ(in[k], value(r, me, k, round)) << "from rank " << r << ", round " << round;
    }
  }
}

TEST(FixedExchange, RefusesToSendToItself) {
  const Comm comm = Comm::world();
  std::vector<std::size_t> sends(static_cast<std::size_t>(comm.size())), receives(sends.size());
  sends[static_cast<std::size_t>(comm.rank())] = 1;
  aniso::FixedExchange exchange;
  EXPECT_ANY_THROW(exchange.resize(comm, sends, receives));
}

} // namespace
