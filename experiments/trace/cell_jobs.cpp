#include "trace/cell_jobs.hpp"

#include <stdexcept>

namespace smithlab::trace {

void CellJobs::put(std::vector<char>& out, const Partial& p) const {
    for (const walk::Moments& m : p.albedo.bins) {
        cluster::mpi::put(out, m.sum);
        cluster::mpi::put(out, m.sum2);
    }
    cluster::mpi::put(out, p.albedo.walks);
    cluster::mpi::put(out, p.albedo.events);
    cluster::mpi::put(out, p.albedo.capped);
    cluster::mpi::put(out, static_cast<std::int64_t>(p.brdf ? p.brdf->cells.size() : 0));
    if (!p.brdf) return;
    for (const walk::Moments& m : p.brdf->cells) {
        cluster::mpi::put(out, m.sum);
        cluster::mpi::put(out, m.sum2);
    }
    cluster::mpi::put(out, p.brdf->walks);
}

CellJobs::Partial CellJobs::get(cluster::mpi::Reader& in, std::size_t j) const {
    Partial p = empty(j);
    for (walk::Moments& m : p.albedo.bins) {
        m.sum = in.get<double>();
        m.sum2 = in.get<double>();
    }
    p.albedo.walks = in.get<std::int64_t>();
    p.albedo.events = in.get<std::int64_t>();
    p.albedo.capped = in.get<std::int64_t>();
    if (in.get<std::int64_t>() != static_cast<std::int64_t>(p.brdf ? p.brdf->cells.size() : 0))
        throw std::runtime_error("trace: a partial tally from another rank does not match " + name(j) + "'s bins");
    if (!p.brdf) return p;
    for (walk::Moments& m : p.brdf->cells) {
        m.sum = in.get<double>();
        m.sum2 = in.get<double>();
    }
    p.brdf->walks = in.get<std::int64_t>();
    return p;
}

}  // namespace smithlab::trace
