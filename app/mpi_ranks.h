#pragma once
// The processes of one render. Under `mpirun` (Open MPI sets OMPI_COMM_WORLD_SIZE; PMIx launchers
// set PMIX_RANK) MPI is initialised on first use and every rank renders its share of the passes;
// otherwise there is one rank and MPI is never touched, so a plain `tyndall render` needs no MPI
// runtime. Rank 0 alone prints, writes images and checkpoints. Call from the main thread only.
#include <cstdint>
#include <vector>

#include "hybrid/pass_distribution.h"

namespace tyndall::app {

/// The MPI world as the render driver's PassDistribution.
class Ranks : public PassDistribution {
public:
    /// The world of this process: initialises MPI the first time when launched by mpirun.
    static Ranks& world();
    ~Ranks() override;

    int rank() const override { return m_rank; }
    int size() const override { return m_size; }
    /// Started by mpirun (even with one rank).
    bool distributed() const override { return m_mpi; }
    void broadcast(std::vector<uint64_t>& values) const override;
    void gather(const std::vector<float>& mine, std::vector<float>* all) const override;
    void gather(const std::vector<uint64_t>& mine, std::vector<uint64_t>* all) const override;
    /// Ends every rank at once with `code` (an error on one rank that the others cannot see).
    [[noreturn]] void abort(int code) const;

private:
    Ranks();
    bool m_mpi = false;
    int m_rank = 0;
    int m_size = 1;
};

}  // namespace tyndall::app
