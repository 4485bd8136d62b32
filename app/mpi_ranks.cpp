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

void Ranks::gather(const std::vector<float>& mine, std::vector<float>* all) const {
    if (!m_mpi) {
        *all = mine;
        return;
    }
    if (m_rank == 0) all->resize(mine.size() * size_t(m_size));
    MPI_Gather(mine.data(), int(mine.size()), MPI_FLOAT, m_rank == 0 ? all->data() : nullptr, int(mine.size()),
               MPI_FLOAT, 0, MPI_COMM_WORLD);
}

void Ranks::gather(const std::vector<uint64_t>& mine, std::vector<uint64_t>* all) const {
    if (!m_mpi) {
        *all = mine;
        return;
    }
    if (m_rank == 0) all->resize(mine.size() * size_t(m_size));
    MPI_Gather(mine.data(), int(mine.size()), MPI_UINT64_T, m_rank == 0 ? all->data() : nullptr, int(mine.size()),
               MPI_UINT64_T, 0, MPI_COMM_WORLD);
}

void Ranks::abort(int code) const {
    if (m_mpi) MPI_Abort(MPI_COMM_WORLD, code);
    std::_Exit(code);
}

}  // namespace tyndall::app
