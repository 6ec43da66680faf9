#include "io/output_file.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <cerrno>
#include <cstring>

namespace bodt {

OutputFile::OutputFile(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "w")) {
    if (!file_) throw Error(BODT_ERR_IO, "cannot open '" + path + "' for writing: " + std::strerror(errno));
}

OutputFile::~OutputFile() {
    if (file_) std::fclose(file_);
}

void OutputFile::close() {
    const bool failed = std::ferror(file_) != 0;
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (failed || !closed) throw Error(BODT_ERR_IO, "writing '" + path_ + "' failed");
}

}  // namespace bodt
