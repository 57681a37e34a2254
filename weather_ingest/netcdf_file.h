// SPDX-License-Identifier: MIT
// NcFile: the only place that calls netCDF-C (NetCDF-3 classic/64-bit offset and NetCDF-4/HDF5). The file
// id is closed by the destructor; every status code becomes an IngestError naming the file and variable.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace sky
{

class NcFile
{
public:
    /// A variable's shape and description.
    struct Variable
    {
        std::string name;
        std::vector<std::string> dimensions;  ///< slowest first
        std::vector<size_t> shape;            ///< lengths, slowest first
        std::string units;
        std::string description;              ///< "description" or "long_name" attribute
    };

    /// Opens read-only. Throws IngestError: Io (cannot open), NotRecognized (not NetCDF), Corrupt.
    explicit NcFile(const std::string& path);
    ~NcFile();
    NcFile(const NcFile&) = delete;
    NcFile& operator=(const NcFile&) = delete;

    const std::string& path() const { return path_; }
    /// "NetCDF-4", "NetCDF-4 classic model", "NetCDF-3 classic", "NetCDF-3 64-bit offset", …
    std::string formatName() const;

    bool hasVariable(const std::string& name) const;
    std::vector<std::string> variableNames() const;
    /// Throws IngestError(MissingFields) naming the variable when absent.
    Variable variable(const std::string& name) const;

    /// Reads a hyperslab converted to float; values equal to _FillValue or missing_value become NaN.
    ///
    /// @param[in] start first index per dimension; count: lengths per dimension (sizes checked against
    ///   the variable's shape, so a bad request is an error, not an out-of-bounds read).
    std::vector<float> readFloat(const std::string& name, const std::vector<size_t>& start,
                                 const std::vector<size_t>& count) const;

    /// Reads a 2D char variable (e.g. WRF Times(Time, DateStrLen)) as one string per row.
    std::vector<std::string> readStrings(const std::string& name) const;

    /// A numeric global attribute (first value), or nothing.
    std::optional<double> globalNumber(const std::string& name) const;

private:
    [[noreturn]] void fail(int status, const std::string& variable, const std::string& what) const;
    int varId(const std::string& name) const;
    std::string path_;
    int id_ = -1;
};

}  // namespace sky
