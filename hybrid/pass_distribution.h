#pragma once
// How the passes of one render are shared among processes (MPI ranks; app/mpi_ranks.h is the MPI
// implementation, single() the one-process one). The render driver (hybrid/pass_scheduler.h) hands
// passes out in rounds of one pass per rank: round k starting at pass `next` gives pass next + r to
// rank r, so which rank renders a pass never depends on timing. Rank 0 decides before each round
// how many passes it holds (the pass target, the time budget, a stop from the display) and
// broadcasts it, so with a time budget all ranks agree on one pass count. The round's pass images
// are gathered to rank 0 and added there in pass order: adding the same float images in the same
// order makes the double sums, and so the image, equal bit for bit to a single-process render of
// the same passes (a reduction of per-rank sums would not: double addition is not associative).
#include <cstdint>
#include <vector>

namespace tyndall {

class PassDistribution {
public:
    virtual ~PassDistribution() = default;

    virtual int rank() const = 0;
    virtual int size() const = 0;
    /// False for the one process of a plain render (the driver may then overlap passes).
    virtual bool distributed() const = 0;
    /// Rank 0's `values` to every rank (the same size everywhere).
    virtual void broadcast(std::vector<uint64_t>& values) const = 0;
    /// Every rank's `mine` (the same size on all ranks), concatenated in rank order, into `all` on
    /// rank 0 (untouched elsewhere).
    virtual void gather(const std::vector<float>& mine, std::vector<float>* all) const = 0;
    virtual void gather(const std::vector<uint64_t>& mine, std::vector<uint64_t>* all) const = 0;

    /// One process: rank 0 of 1, broadcast a no-op, gather a copy.
    static const PassDistribution& single();
};

}  // namespace tyndall
