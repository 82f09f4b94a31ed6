#include "cluster/mpi_world.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "output/signal_cleanup.hpp"

#ifdef SMITHLAB_MPI
#include <mpi.h>
#endif

namespace smithlab::cluster::mpi {

namespace {
// started and launched serve the MPI build only.
[[maybe_unused]] bool started = false;
bool is_talking = false;
int world_rank = 0, world_size = 1;

// Open MPI's mpirun, and the PMI / PMIx launchers (srun, hydra) set these; a plain start sets none of them.
[[maybe_unused]] bool launched() {
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
    // A failed call (a rank died mid-message) comes back here (check) instead of aborting the process unheard.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

namespace {
// A communication that failed -- a rank that died with a message on its way: said, then the process ends as on
// mpirun's SIGTERM (the notes printed, the temporaries removed: output/signal_cleanup.hpp). The library's default
// handler would abort rank 0 before mpirun's signal comes, and the note of what each rank held would never be printed.
void check(int rc, const char* call) {
    if (rc == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(rc, text, &length);
    std::fprintf(stderr, "smithlab: rank %d: %s failed (%.*s): a rank has died?\n", world_rank, call, length, text);
    // mpirun's own SIGTERM follows a dead rank within ~1 s and names it: let it come first (the signal thread takes it
    // as usual), so that this rank is not reported as the one that failed.
    std::this_thread::sleep_for(std::chrono::seconds(3));
    output::end_as_signalled(SIGTERM);
}
}  // namespace

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
    check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD), "MPI_Send");
}

namespace {
std::vector<char> receive(MPI_Status& st) {
    int n = 0;
    check(MPI_Get_count(&st, MPI_BYTE, &n), "MPI_Get_count");
    std::vector<char> bytes(static_cast<std::size_t>(n));
    check(MPI_Recv(bytes.data(), n, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
          "MPI_Recv");
    return bytes;
}
}  // namespace

std::optional<Message> try_recv_any() {
    if (!started) no_mpi();
    MPI_Status st;
    int arrived = 0;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &st), "MPI_Iprobe");
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
        check(MPI_Iprobe(from, tag, MPI_COMM_WORLD, &arrived, &st), "MPI_Iprobe");
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

}  // namespace smithlab::cluster::mpi
