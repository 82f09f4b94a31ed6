// A section of the report (the G1 table, the G2 table, the sampling experiment, the walk, the figures): the keys of
// the scene it reads, its share of the work estimate, its checks, its computation, and what it writes. run_report
// (report.hpp) takes a list of them (sections.hpp: the built-in list) and runs each phase over all of them in turn:
//   read      every section reads its keys of the scene (parse_scene);
//   add_work  the work is estimated from the scene alone (work_estimate.hpp), and a scene too large is refused;
//   check     every section checks its domains and builds its input: nothing is computed before all have passed;
//   compute   the work that needs neither the references nor the timing: on rank 0, or under MPI on every rank
//             together where on_all_ranks() (the walk);
//   measure   against the reference cache (references.hpp), rank 0;
//   add_timing  what to time: every item of every section is timed in one Google Benchmark run (timing.hpp);
//   write     its files in the output directory and its part of report.md, in the list's order;
// and then, when any section draws(), report_plots.py draws every figure from the files written.
// A section that the scene does not name does nothing in any phase (and may still count a 0 in the work estimate).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "report/references.hpp"
#include "report/settings.hpp"
#include "report/timing.hpp"
#include "report/work_estimate.hpp"
#include "scene/strict_table.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/variants.hpp"

namespace smithlab::report {

class Section {
public:
    virtual ~Section() = default;

    // The scene's top-level keys (tables, arrays of tables) this section reads: "g2"; the G1 table's "ndf" and
    // "variants". Every other top-level key of a scene is refused unless another section or the settings read it.
    virtual std::vector<std::string> keys() const = 0;
    // Reads those keys from the scene's document, strictly (an input_error "FILE:LINE: key ..."); the settings (the
    // scene's title, [grid], [timing], [figures]) are read before any section.
    virtual void read(scene::StrictTable& doc, const Settings& settings, const NdfRegistry& ndfs) = 0;
    // Its evaluations, estimated from the scene alone (parts named as the work's message shows them).
    virtual void add_work(Work& work, const Settings& settings, const VariantRegistry& variants) const = 0;
    // Its domains checked and its input built, before any section computes: an input_error naming the key.
    virtual void check(const Settings& settings, const NdfRegistry& ndfs, const VariantRegistry& variants) = 0;

    // Whether compute() runs on every MPI rank together (the ranks share its work); otherwise rank 0 alone runs it.
    virtual bool on_all_ranks() const { return false; }
    virtual void compute() {}
    // Rank 0: against the references, read from and saved to the cache.
    virtual void measure(ReferenceCache&) {}
    // Rank 0: the items to time; their ns is set before write().
    virtual void add_timing(Timing&) {}
    // Rank 0: its files in dir, and its part appended to dir/report.md.
    virtual void write(const std::filesystem::path& dir, const Settings& settings) = 0;
    // Whether report_plots.py has a figure of it to draw.
    virtual bool draws(const Settings&) const { return false; }
};

using Sections = std::vector<std::unique_ptr<Section>>;

}  // namespace smithlab::report
