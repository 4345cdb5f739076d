#include "codec/trajectory_csv.h"

#include <sstream>

namespace spinfold {

using nlohmann::ordered_json;

namespace {

constexpr const char* kColumns[] = {"r",  "phi", "lambda", "mu",    "det_L", "energy", "energy_error",
                                    "X0", "X1",  "X2",     "status"};

std::string quoted(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// One body's cells, in the order of kColumns.
void write_block(std::ostringstream& csv, const ordered_json& sample) {
  const auto cell = [](const ordered_json& v) {
    return v.is_null() ? std::string() : v.is_string() ? quoted(v.get<std::string>()) : v.dump();
  };
  const ordered_json X = sample.contains("X") ? sample.at("X") : ordered_json();
  for (const char* column : kColumns) {
    const std::string name(column);
    if (name.size() == 2 && name[0] == 'X')
      csv << "," << cell(X.is_array() ? X[name[1] - '0'] : ordered_json());
    else
      csv << "," << cell(sample.contains(name) ? sample.at(name) : ordered_json());
  }
}

}  // namespace

std::string trajectory_csv(std::span<const ordered_json> samples) {
  std::ostringstream csv;
  csv << "t";
  for (const char* column : kColumns) csv << "," << column;
  const ordered_json none = ordered_json::array();
  const ordered_json& companions =
      samples.empty() || !samples.back().contains("companions") ? none : samples.back().at("companions");
  for (const ordered_json& c : companions)
    for (const char* column : kColumns) csv << "," << quoted(c.value("label", std::string()) + "." + column);
  csv << "\n";
  for (const ordered_json& sample : samples) {
    csv << (sample.contains("t") && !sample.at("t").is_null() ? sample.at("t").dump() : std::string());
    write_block(csv, sample);
    for (std::size_t i = 0; i < companions.size(); ++i)
      write_block(csv, sample.contains("companions") && i < sample.at("companions").size()
                           ? sample.at("companions").at(i)
                           : ordered_json::object());
    csv << "\n";
  }
  return csv.str();
}

}  // namespace spinfold
