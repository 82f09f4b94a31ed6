// The bounds every scene is held to when it is read, before any work starts, each with its reason. A scene that
// exceeds one is refused with a message naming the key, the bound and, for the two size bounds, the flag that
// raises them.
#pragma once

#include <cmath>
#include <cstddef>

namespace smithlab::scene {

// A scene file's size: the default scenes are 2-6 KB and an axis of any length is written {log = [lo, hi], n = N},
// so 1 MiB is far beyond any scene written by hand, and it refuses /dev/zero, an endless pipe or a mistaken large
// file before its text is held in memory.
inline constexpr std::size_t max_scene_bytes = std::size_t{1} << 20;

// The nesting of lists and inline tables ([[[...]]], {a = {b = ...}}), table headers included: toml11 reads nesting
// by recursion, so a deep scene would end in a stack overflow. A scene uses 2 or 3 levels; 64 leaves room for
// anything written by hand and is ~100x inside the depth that overflows an 8 MiB stack.
inline constexpr int max_nesting_depth = 64;

// What a trace or fit scene may ask for unless --max-cells / --max-walks raise it, and the --scale it runs at.
struct SizeLimits {
    // Cells of a trace (NDFs x materials x theta_i x phi_i, each [brdf] bin counting as a cell: a cell file and
    // ~16 rows of albedo.csv, a bin 16 rows of brdf.csv and 384 bytes of tallies) or points of a fit (NDFs x
    // training alpha x direction pairs, plus the validation points and directions). 1e6 cells are ~2 GB of CSV
    // and a million files in DIR/cells; the default trace sweep has 48, the default fit 4435.
    double max_cells = 1e6;
    // Walks in all: cells x walks per cell. 1e11 walks are hours on 16 cores (0.1-1 us a walk on one core); the
    // default trace sweep has 9.6e6, the default fit 1.7e8.
    double max_walks = 1e11;
    // --scale F: every count of random samples the scene asks for (walks, the sampling experiment's samples, a fit
    // table's check-grid refinement) times F, each kept at its key's least value, and the report's benchmark time
    // times F. The same scene through the same code at a fraction (F < 1) or a multiple of its cost: the test
    // main_job runs every default scene at F = 0.01. Applied before the bounds above are checked.
    double scale = 1.0;
};

// n x scale rounded, and at least `least` (a count the scene's reader would accept).
inline long long scaled_count(long long n, double scale, long long least) {
    const double s = std::round(static_cast<double>(n) * scale);
    return s < static_cast<double>(least) ? least : static_cast<long long>(s);
}

}  // namespace smithlab::scene
