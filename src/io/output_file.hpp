// A FILE* opened for writing that reports every failure as Error(BODT_ERR_IO).
#pragma once

#include <cstdio>
#include <string>

namespace bodt {

class OutputFile {
public:
    explicit OutputFile(const std::string& path);
    ~OutputFile();
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    FILE* get() const { return file_; }
    // Flushes and closes; throws if anything written so far failed.
    void close();

private:
    std::string path_;
    FILE* file_;
};

}  // namespace bodt
