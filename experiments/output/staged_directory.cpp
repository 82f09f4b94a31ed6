#include "output/staged_directory.hpp"

#include <stdexcept>

#include "output/output_file.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::output {

namespace fs = std::filesystem;

void require_output_directory(const fs::path& out) {
    std::error_code ec;
    const fs::file_status st = fs::status(out, ec);
    if (st.type() != fs::file_type::not_found && st.type() != fs::file_type::directory)
        throw input_error("output directory '" + out.string() + "' exists and is not a directory");
}

StagedDirectory::StagedDirectory(const fs::path& out, const std::string& name) : out_(out) {
    require_output_directory(out);
    std::error_code ec;
    for (fs::path p = fs::absolute(out, ec); !ec && !p.empty() && !fs::exists(p, ec); p = p.parent_path())
        created_.push_back(p);
    fs::create_directories(out, ec);
    if (ec) throw input_error("output directory '" + out.string() + "' cannot be created: " + ec.message());
    remove_stale_temporaries(out, name);
    stage_.emplace(out / temporary_name(name));
    fs::create_directories(stage_->path(), ec);
    if (ec) throw input_error("output directory '" + out.string() + "' is not writable: " + ec.message());
}

StagedDirectory::~StagedDirectory() {
    std::error_code ignored;
    if (!stage_) return;
    fs::remove_all(stage_->path(), ignored);
    for (const fs::path& p : created_) fs::remove(p, ignored);  // only if empty: a saved cache stays
}

void StagedDirectory::publish() {
    const fs::path& stage = stage_->path();
    std::vector<fs::directory_entry> entries(fs::recursive_directory_iterator(stage), {});  // before moving any
    for (const fs::directory_entry& entry : entries) {
        const fs::path target = out_ / fs::relative(entry.path(), stage);
        if (entry.is_directory()) {
            if (!fs::is_directory(target)) fs::create_directories(target);
            continue;
        }
        std::error_code ec;
        fs::rename(entry.path(), target, ec);
        if (ec) throw input_error("cannot move '" + target.string() + "' into place: " + ec.message());
    }
    std::error_code ignored;
    fs::remove_all(stage, ignored);
    stage_.reset();
}

void finish(std::ofstream& out, const std::filesystem::path& path) {
    out.close();
    if (!out) throw std::runtime_error("could not write " + path.string() + " (disk full?)");
}

void write_file(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    finish(out, path);
}

}  // namespace smithlab::output
