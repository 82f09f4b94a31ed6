// trace/cell_file.hpp -- a finished cell's file, OUT/cells/cell-NNNNNN.csv (trace_run.hpp: how a run resumes).
//
// Its lines, in order:
//   key,KEY            everything that defines the cell's bits (cell_key), one CSV field
//   bounces,N          facet hits of all its walks
//   capped,N           walks ended at the event cap
//   total,VALUE,STDERR the albedo over every hemisphere, order and component
//   a,ROW              one per row of albedo.csv, as trace_rows.hpp writes it (without the NDF parameter columns)
//   b,ROW              one per row of brdf.csv, likewise
//   checksum,HEX       the CRC-64 of every byte above, the key line included (smithlab/util/checksum.hpp)
// Numbers with 17 significant digits: they round-trip.
//
// A file is reused only when its checksum holds, its key is the one asked for, its counts are integers, its numbers
// finite and its rows as many as the cell has: a file cut short, with a value edited, bits flipped or rows swapped
// fails the checksum and is traced again, and the run says so on stderr ("trace: cell 3: checksum mismatch, traced
// again"). A whole file under another key (the scene changed since) is traced again without a word.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "smithlab/any_ndf.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/tally.hpp"
#include "trace/trace_scene.hpp"

namespace smithlab::trace {

// What a finished cell leaves: its rows as the output files hold them, but for the NDF parameter columns.
struct CellRows {
    std::int64_t bounces = 0, capped = 0;
    walk::Estimate total{0.0, 0.0};
    std::vector<std::string> albedo, brdf;
};

std::filesystem::path cell_path(const std::filesystem::path& out, std::uint64_t index);

// The key line's text: version, NDF (its key: a table's contents too), material, direction, walks, seed, cell index,
// max_order, downward, hit_normal, brdf bins; not the thread count, which changes no bit.
std::string cell_key(const CellSettings& settings, const TraceCell& cell, const AnyNdf& ndf, const walk::Material& m);

// Written atomically (output::write_output): a killed run leaves the file whole or absent.
void write_cell(const std::filesystem::path& path, const std::string& key, const CellRows& rows);

// The file's rows, if its checksum holds, its key is `key`, its numbers are finite and it holds `albedo_rows` and
// `brdf_rows` rows; else none (the cell is traced again; a present file whose checksum fails is named on stderr).
std::optional<CellRows> read_cell(const std::filesystem::path& path, const std::string& key, std::size_t albedo_rows,
                                  std::size_t brdf_rows);

}  // namespace smithlab::trace
