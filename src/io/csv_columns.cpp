#include "crane_twin/io/csv_columns.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "crane_twin/io/input_error.hpp"

namespace crane_twin {

namespace {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> v;
  std::stringstream ss(line);
  for (std::string x; std::getline(ss, x, ',');) v.push_back(x);
  if (!line.empty() && line.back() == ',') v.push_back("");
  return v;
}

double parseNumber(const std::string& s, const std::string& file, int line,
                   const std::string& column) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size() || !std::isfinite(v)) {
    throw InputError(file + ": line " + std::to_string(line) + ", column '" + column +
                     "': not a finite number: '" + s + "'");
  }
  return v;
}

}  // namespace

std::vector<std::vector<double>> readCsvColumns(const std::string& file,
                                                const std::vector<std::string>& wanted) {
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot open for reading");
  std::string line;
  if (!std::getline(in, line)) throw InputError(file + ": empty file (no header row)");
  const std::vector<std::string> header = splitCsv(line);
  std::vector<int> index;
  for (const auto& w : wanted) {
    int k = -1;
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == w) k = static_cast<int>(i);
    if (k < 0) {
      std::string names;
      for (const auto& h : header) names += (names.empty() ? "" : ", ") + h;
      throw InputError(file + ": header has no column '" + w + "' (it has: " + names + ")");
    }
    index.push_back(k);
  }
  std::vector<std::vector<double>> rows;
  int lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty()) continue;
    const std::vector<std::string> f = splitCsv(line);
    if (f.size() != header.size()) {
      throw InputError(file + ": line " + std::to_string(lineNo) + ": " + std::to_string(f.size()) +
                       " fields, header has " + std::to_string(header.size()));
    }
    std::vector<double> r;
    for (std::size_t i = 0; i < index.size(); ++i) {
      r.push_back(parseNumber(f[index[i]], file, lineNo, wanted[i]));
    }
    rows.push_back(std::move(r));
  }
  if (rows.empty()) throw InputError(file + ": no data rows");
  return rows;
}

}  // namespace crane_twin
