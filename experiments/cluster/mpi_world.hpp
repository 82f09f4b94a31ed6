// cluster/mpi_world.hpp -- the executable's only view of MPI: lib/ stays MPI-free, and without SMITHLAB_MPI
// (or when not started by a launcher such as mpirun) the world is one rank and nothing here talks to anyone.
//
// Only the thread that called init() calls MPI (MPI_THREAD_FUNNELED): a rank's worker threads trace, its main thread
// communicates. Messages are raw bytes (the partial tallies as the doubles and int64s they hold): the ranks are the
// same build on machines of one byte order.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace smithlab::cluster::mpi {

// MPI_Init_thread when this process was started by an MPI launcher (Open MPI's or a PMI's environment), else nothing.
// Call once, first thing in main; finalize() at its end (MPI_Finalize when init() started MPI).
void init(int& argc, char**& argv);
void finalize();

bool compiled();  // SMITHLAB_MPI
int rank();       // 0 without MPI
int size();       // 1 without MPI

// Set when the ranks start talking (they have checked their input alike up to there): an error after it ends the
// job with abort(), one before it is every rank's and each ends as a single process would, rank 0 saying why.
void set_talking();
bool talking();

// Ends every rank of the job at once (MPI_Abort), for an error after the ranks started talking: the others would
// wait forever. Returns only without MPI.
void abort(int code);

// Point-to-point messages of bytes with a tag. send blocks until the bytes are handed over; recv waits for the
// message (polling, with sleeps from 10 us doubling to 1 ms, not spinning a core: a waiting rank leaves its cores
// to the others); try_recv_any takes a message from any rank if one has arrived.
void send(int to, int tag, const std::vector<char>& bytes);
struct Message {
    int from = 0, tag = 0;
    std::vector<char> bytes;
};
std::optional<Message> try_recv_any();
std::vector<char> recv(int from, int tag);

// The bytes of trivially copyable values, appended and read back in order.
template <class T>
void put(std::vector<char>& out, const T& v) {
    const char* p = reinterpret_cast<const char*>(&v);
    out.insert(out.end(), p, p + sizeof(T));
}
class Reader {
public:
    explicit Reader(const std::vector<char>& b) : b_(b) {}
    template <class T>
    T get();
    bool done() const { return at_ == b_.size(); }

private:
    const std::vector<char>& b_;
    std::size_t at_ = 0;
};

}  // namespace smithlab::cluster::mpi

#include <cstring>
#include <stdexcept>

template <class T>
T smithlab::cluster::mpi::Reader::get() {
    if (b_.size() - at_ < sizeof(T)) throw std::runtime_error("mpi: a message shorter than its contents");
    T v;
    std::memcpy(&v, b_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
}
