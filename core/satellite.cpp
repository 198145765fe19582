#include "core/satellite.hpp"

#include <fmt/format.h>

namespace navemu {

std::string SatId::rinex() const { return fmt::format("{}{:02d}", info().rinex_letter, number()); }

std::optional<SatId> SatId::from_rinex(char letter, int number) {
  if (number < 1 || number > 99) return std::nullopt;
  for (const GnssSystemInfo& s : kGnssSystems)
    if (s.rinex_letter == letter) return SatId(s.system, number);
  return std::nullopt;
}

std::optional<SatId> SatId::from_ubx(int gnss_id, int sv_id) {
  for (const GnssSystemInfo& s : kGnssSystems) {
    if (s.ubx_gnss_id != gnss_id) continue;
    const SatId id(s.system, sv_id - s.ubx_sv_offset);
    if (sv_id - s.ubx_sv_offset < 1 || !id.defined()) return std::nullopt;
    return id;
  }
  return std::nullopt;
}

std::optional<int> SatId::ubx_legacy_sv_id() const {
  const int n = number();
  if (system() == GnssSystem::kGps) return n;
  if (!defined()) return std::nullopt;
  switch (system()) {
    case GnssSystem::kGps:
    case GnssSystem::kSbas:
      return n + info().ubx_sv_offset;
    case GnssSystem::kGalileo:
      return 210 + n;
    case GnssSystem::kBeidou:
      return n <= 5 ? 158 + n : n <= 37 ? 27 + n : std::optional<int>();
    case GnssSystem::kQzss:
      return 192 + n;
    case GnssSystem::kGlonass:
      return 64 + n;
    case GnssSystem::kNavic:
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<int> SatId::nmea_id(NmeaNumbering numbering) const {
  const int n = number();
  const bool v411 = numbering == NmeaNumbering::kV411;
  if (system() != GnssSystem::kGps && !defined()) return std::nullopt;
  switch (system()) {
    case GnssSystem::kGps:
      return n;
    case GnssSystem::kSbas:  // PRN 120-151 as 33-64, PRN 152-158 as themselves
      return n <= 51 ? n + 13 : n + 100;
    case GnssSystem::kGlonass:
      return 64 + n;
    case GnssSystem::kQzss:
      return v411 ? n : n + 192;
    case GnssSystem::kGalileo:
      return v411 ? n : 300 + n;
    case GnssSystem::kBeidou:
      return v411 ? n : 400 + n;
    case GnssSystem::kNavic:
      return v411 ? std::optional<int>(n) : std::nullopt;
  }
  return std::nullopt;
}

}  // namespace navemu
