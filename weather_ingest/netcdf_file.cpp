// SPDX-License-Identifier: MIT
#include "weather_ingest/netcdf_file.h"

#include "weather_ingest/ingest_error.h"

#include <netcdf.h>

#include <cmath>

namespace sky
{
namespace
{

std::string textAttribute(int id, int var, const char* name)
{
    size_t len = 0;
    nc_type type = NC_NAT;
    if (nc_inq_att(id, var, name, &type, &len) != NC_NOERR || type != NC_CHAR || len > 4096)
        return {};
    std::string s(len, '\0');
    if (nc_get_att_text(id, var, name, s.data()) != NC_NOERR)
        return {};
    while (!s.empty() && s.back() == '\0')
        s.pop_back();
    return s;
}

std::optional<double> numberAttribute(int id, int var, const char* name)
{
    size_t len = 0;
    nc_type type = NC_NAT;
    if (nc_inq_att(id, var, name, &type, &len) != NC_NOERR || type == NC_CHAR || type == NC_STRING || len < 1)
        return std::nullopt;
    std::vector<double> v(len);
    if (nc_get_att_double(id, var, name, v.data()) != NC_NOERR)
        return std::nullopt;
    return v[0];
}

}  // namespace

NcFile::NcFile(const std::string& path) : path_(path)
{
    const int status = nc_open(path.c_str(), NC_NOWRITE, &id_);
    if (status == NC_NOERR)
        return;
    id_ = -1;
    const IngestErrorKind kind = status == ENOENT || status == EACCES || status == EISDIR ? IngestErrorKind::Io
                                 : status == NC_ENOTNC                                 ? IngestErrorKind::NotRecognized
                                                                                       : IngestErrorKind::Corrupt;
    throw IngestError(kind, path, "", "", std::string("netCDF: ") + nc_strerror(status));
}

NcFile::~NcFile()
{
    if (id_ >= 0)
        nc_close(id_);
}

void NcFile::fail(int status, const std::string& variable, const std::string& what) const
{
    throw IngestError(IngestErrorKind::Corrupt, path_, variable.empty() ? "" : "variable " + variable, "",
                      what + ": netCDF: " + nc_strerror(status));
}

std::string NcFile::formatName() const
{
    int format = 0;
    if (nc_inq_format(id_, &format) != NC_NOERR)
        return "NetCDF";
    switch (format)
    {
    case NC_FORMAT_CLASSIC: return "NetCDF-3 classic";
    case NC_FORMAT_64BIT_OFFSET: return "NetCDF-3 64-bit offset";
    case NC_FORMAT_CDF5: return "NetCDF-3 CDF-5";
    case NC_FORMAT_NETCDF4: return "NetCDF-4";
    case NC_FORMAT_NETCDF4_CLASSIC: return "NetCDF-4 classic model";
    default: return "NetCDF";
    }
}

int NcFile::varId(const std::string& name) const
{
    int var = -1;
    const int status = nc_inq_varid(id_, name.c_str(), &var);
    if (status != NC_NOERR)
        throw IngestError(IngestErrorKind::MissingFields, path_, "variable " + name, "", "variable is missing");
    return var;
}

bool NcFile::hasVariable(const std::string& name) const
{
    int var = -1;
    return nc_inq_varid(id_, name.c_str(), &var) == NC_NOERR;
}

std::vector<std::string> NcFile::variableNames() const
{
    int count = 0;
    if (const int status = nc_inq_nvars(id_, &count); status != NC_NOERR)
        fail(status, "", "listing variables");
    std::vector<std::string> names;
    for (int v = 0; v < count; ++v)
    {
        char name[NC_MAX_NAME + 1] = {};
        if (nc_inq_varname(id_, v, name) == NC_NOERR)
            names.emplace_back(name);
    }
    return names;
}

NcFile::Variable NcFile::variable(const std::string& name) const
{
    const int var = varId(name);
    int ndims = 0;
    if (const int status = nc_inq_varndims(id_, var, &ndims); status != NC_NOERR || ndims > NC_MAX_VAR_DIMS)
        fail(status, name, "reading dimensions");
    std::vector<int> dims(static_cast<size_t>(ndims));
    if (const int status = nc_inq_vardimid(id_, var, dims.data()); status != NC_NOERR)
        fail(status, name, "reading dimensions");
    Variable v;
    v.name = name;
    for (int d : dims)
    {
        char dimName[NC_MAX_NAME + 1] = {};
        size_t len = 0;
        if (const int status = nc_inq_dim(id_, d, dimName, &len); status != NC_NOERR)
            fail(status, name, "reading a dimension");
        v.dimensions.emplace_back(dimName);
        v.shape.push_back(len);
    }
    v.units = textAttribute(id_, var, "units");
    v.description = textAttribute(id_, var, "description");
    if (v.description.empty())
        v.description = textAttribute(id_, var, "long_name");
    return v;
}

std::vector<float> NcFile::readFloat(const std::string& name, const std::vector<size_t>& start,
                                     const std::vector<size_t>& count) const
{
    const Variable v = variable(name);
    if (start.size() != v.shape.size() || count.size() != v.shape.size())
        throw IngestError(IngestErrorKind::Corrupt, path_, "variable " + name, "",
                          "has " + std::to_string(v.shape.size()) + " dimensions, expected " +
                              std::to_string(start.size()));
    size_t total = 1;
    for (size_t d = 0; d < start.size(); ++d)
    {
        if (start[d] + count[d] > v.shape[d])
            throw IngestError(IngestErrorKind::Corrupt, path_, "variable " + name, "",
                              "dimension " + v.dimensions[d] + " has " + std::to_string(v.shape[d]) +
                                  " entries, " + std::to_string(start[d] + count[d]) + " needed");
        total *= count[d];
    }
    std::vector<float> out(total);
    const int var = varId(name);
    if (const int status = nc_get_vara_float(id_, var, start.data(), count.data(), out.data()); status != NC_NOERR)
        fail(status, name, "reading values");
    for (const char* attr : {"_FillValue", "missing_value"})
    {
        const std::optional<double> fill = numberAttribute(id_, var, attr);
        if (!fill)
            continue;
        const auto f = static_cast<float>(*fill);
        for (float& x : out)
            if (x == f)
                x = NAN;
    }
    return out;
}

std::vector<std::string> NcFile::readStrings(const std::string& name) const
{
    const Variable v = variable(name);
    if (v.shape.size() != 2 || v.shape[1] > 1024 || v.shape[0] > 1000000)
        throw IngestError(IngestErrorKind::Corrupt, path_, "variable " + name, "", "expected a (rows, chars) array");
    std::string buf(v.shape[0] * v.shape[1], '\0');
    const size_t start[2] = {0, 0};
    const size_t count[2] = {v.shape[0], v.shape[1]};
    if (const int status = nc_get_vara_text(id_, varId(name), start, count, buf.data()); status != NC_NOERR)
        fail(status, name, "reading text");
    std::vector<std::string> rows;
    for (size_t r = 0; r < v.shape[0]; ++r)
        rows.push_back(buf.substr(r * v.shape[1], v.shape[1]).c_str());
    return rows;
}

std::optional<double> NcFile::globalNumber(const std::string& name) const
{
    return numberAttribute(id_, NC_GLOBAL, name.c_str());
}

}  // namespace sky
