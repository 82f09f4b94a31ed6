#include "mpi_world.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>
#include <stdexcept>

#ifdef SMITHLAB_MPI
#include <mpi.h>
#endif

namespace smithlab::mpi {

namespace {
bool started = false, is_talking = false;
int world_rank = 0, world_size = 1;

// Open MPI's mpirun, and the PMI / PMIx launchers (srun, hydra) set these; a plain start sets none of them.
bool launched() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
        if (std::getenv(v)) return true;
    return false;
}

[[noreturn]] void no_mpi() { throw std::logic_error("mpi: called in a process without MPI"); }
}  // namespace

bool compiled() {
#ifdef SMITHLAB_MPI
    return true;
#else
    return false;
#endif
}

int rank() { return world_rank; }
void set_talking() { is_talking = true; }
bool talking() { return is_talking; }
int size() { return world_size; }

#ifdef SMITHLAB_MPI

void init(int& argc, char**& argv) {
    if (started || !launched()) return;
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    started = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &world_size);
}

void finalize() {
    if (!started) return;
    started = false;
    MPI_Finalize();
}

void abort(int code) {
    if (started && world_size > 1) MPI_Abort(MPI_COMM_WORLD, code);
}

void send(int to, int tag, const std::vector<char>& bytes) {
    if (!started) no_mpi();
    MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

namespace {
std::vector<char> receive(MPI_Status& st) {
    int n = 0;
    MPI_Get_count(&st, MPI_BYTE, &n);
    std::vector<char> bytes(static_cast<std::size_t>(n));
    MPI_Recv(bytes.data(), n, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return bytes;
}
}  // namespace

std::optional<Message> try_recv_any() {
    if (!started) no_mpi();
    MPI_Status st;
    int arrived = 0;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &st);
    if (!arrived) return std::nullopt;
    Message m{st.MPI_SOURCE, st.MPI_TAG, {}};
    m.bytes = receive(st);
    return m;
}

// MPI_Probe would spin a core while it waits (Open MPI polls); a rank that waits sleeps between probes instead.
std::vector<char> recv(int from, int tag) {
    if (!started) no_mpi();
    MPI_Status st;
    std::chrono::microseconds nap{10};  // doubling to 1 ms: prompt when the message is near, idle when it is not
    for (int arrived = 0;;) {
        MPI_Iprobe(from, tag, MPI_COMM_WORLD, &arrived, &st);
        if (arrived) return receive(st);
        std::this_thread::sleep_for(nap);
        nap = std::min(2 * nap, std::chrono::microseconds(1000));
    }
}

#else

void init(int&, char**&) {}
void finalize() {}
void abort(int) {}
void send(int, int, const std::vector<char>&) { no_mpi(); }
std::optional<Message> try_recv_any() { no_mpi(); }
std::vector<char> recv(int, int) { no_mpi(); }

#endif

}  // namespace smithlab::mpi
