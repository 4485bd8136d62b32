#include "app/mpi_ranks.h"

#include <mpi.h>

#include <cstdlib>

namespace tyndall::app {

namespace {
bool launchedByMpi() {
    return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_SIZE");
}
}  // namespace

Ranks& Ranks::world() {
    static Ranks ranks;
    return ranks;
}

Ranks::Ranks() {
    if (!launchedByMpi()) return;
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) MPI_Init(nullptr, nullptr);
    m_mpi = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &m_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &m_size);
}

Ranks::~Ranks() {
    int finalized = 0;
    if (m_mpi && (MPI_Finalized(&finalized), !finalized)) MPI_Finalize();
}

void Ranks::broadcast(std::vector<uint64_t>& values) const {
    if (m_mpi) MPI_Bcast(values.data(), int(values.size()), MPI_UINT64_T, 0, MPI_COMM_WORLD);
}

namespace {
/// Rank 0's `all` receives every rank's `mine` in rank order (each rank's the same length); without
/// MPI, `mine` itself.
template <class T>
void gatherToRankZero(bool mpi, int rank, int size, const std::vector<T>& mine, std::vector<T>* all,
                      MPI_Datatype type) {
    if (!mpi) {
        *all = mine;
        return;
    }
    if (rank == 0) all->resize(mine.size() * size_t(size));
    MPI_Gather(mine.data(), int(mine.size()), type, rank == 0 ? all->data() : nullptr, int(mine.size()), type, 0,
               MPI_COMM_WORLD);
}
}  // namespace

void Ranks::gather(const std::vector<float>& mine, std::vector<float>* all) const {
    gatherToRankZero(m_mpi, m_rank, m_size, mine, all, MPI_FLOAT);
}

void Ranks::gather(const std::vector<uint64_t>& mine, std::vector<uint64_t>* all) const {
    gatherToRankZero(m_mpi, m_rank, m_size, mine, all, MPI_UINT64_T);
}

void Ranks::abort(int code) const {
    if (m_mpi) MPI_Abort(MPI_COMM_WORLD, code);
    std::_Exit(code);
}

}  // namespace tyndall::app
