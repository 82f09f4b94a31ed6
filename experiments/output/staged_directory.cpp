#include "output/staged_directory.hpp"

#include <cerrno>

#include "output/checked_file.hpp"
#include "output/output_file.hpp"
#include "output/write_error.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::output {

namespace fs = std::filesystem;

void require_output_directory(const fs::path& out) {
    const std::string shown = "output directory '" + out.string() + "'";
    std::error_code ec;
    const fs::file_status st = fs::status(out, ec);
    if (st.type() == fs::file_type::not_found && fs::is_symlink(fs::symlink_status(out, ec)))
        throw input_error(shown + " is a dangling symbolic link to '" + fs::read_symlink(out, ec).string() + "'");
    if (st.type() != fs::file_type::not_found && st.type() != fs::file_type::directory)
        throw input_error(shown + " exists and is not a directory");
    fs::path p = fs::absolute(out, ec);  // the directory, or the nearest existing one it is to be created in
    while (!p.empty() && p != p.root_path() && !fs::exists(p, ec)) p = p.parent_path();
    if (const std::string why = unwritable(p); !why.empty())
        throw input_error(shown + (p == fs::absolute(out, ec) ? " " : ": its parent '" + p.string() + "' ") + why);
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
    errno = 0;
    out.close();
    if (!out) throw write_error(published_name(path.string()), errno);
}

void write_file(const std::filesystem::path& path, const std::string& text) {
    CheckedFile out(path.string(), published_name(path.string()));
    out.stream() << text;
    out.close();
}

}  // namespace smithlab::output
