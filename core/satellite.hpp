#pragma once
// Satellite identities (../shared/DESIGN.md, "Identities, not integers"): a satellite is its
// system and its number, and the numberings of the formats it is written in convert here.
//
// The number is the satellite's RINEX number (RINEX 3.05 section 3.5, "Satellite numbers"): the
// PRN for GPS, Galileo, BeiDou and NavIC, the slot number for GLONASS, PRN - 100 for SBAS and
// PRN - 192 for QZSS. Every satellite a RINEX file can name ("G07", "S20", "J01") thus has an
// id; the numbers each system defines (GnssSystemInfo) are those per-satellite tables hold
// (core/sat_table.hpp).

#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace navemu {

// In the order of u-blox's gnssId (which skips IMES), so that satellites sort as u-blox lists
// them.
enum class GnssSystem : std::uint8_t { kGps, kSbas, kGalileo, kBeidou, kQzss, kGlonass, kNavic };
inline constexpr std::size_t kGnssSystemCount = 7;

// How a system's satellites are named and numbered in each format.
struct GnssSystemInfo {
  GnssSystem system;
  const char* name;
  char rinex_letter;  // RINEX 3.05 section 3.5
  // The satellite numbers (RINEX numbering) the system defines.
  int first_number, last_number;
  // u-blox gnssId and svId = number + ubx_sv_offset (ZED-F9P interface description
  // UBX-18010854, appendix A "Satellite numbering"; F9 HPG L1L5 1.40, UBX-23006991, adds NavIC).
  std::uint8_t ubx_gnss_id;
  int ubx_sv_offset;
  // NMEA 0183 4.11 GNSS system ID (GSA, GSV): 1 GPS (and SBAS), 2 GLONASS, 3 Galileo, 4 BeiDou,
  // 5 QZSS, 6 NavIC.
  int nmea_system_id;
};

// GPS: PRNs 1-63, those IS-GPS-200 assigns C/A codes (Tables 3-Ia, 3-Ib). SBAS: PRNs 120-158
// (u-blox svId range), RINEX S20-S58. Galileo: SVIDs 1-36. BeiDou: PRNs 1-63. QZSS: PRNs 193-202,
// RINEX J01-J10 and u-blox svId 1-10. GLONASS: slots 1-32 (u-blox svId range). NavIC: 1-14.
inline constexpr std::array<GnssSystemInfo, kGnssSystemCount> kGnssSystems{{
    {GnssSystem::kGps, "GPS", 'G', 1, 63, 0, 0, 1},
    {GnssSystem::kSbas, "SBAS", 'S', 20, 58, 1, 100, 1},
    {GnssSystem::kGalileo, "Galileo", 'E', 1, 36, 2, 0, 3},
    {GnssSystem::kBeidou, "BeiDou", 'C', 1, 63, 3, 0, 4},
    {GnssSystem::kQzss, "QZSS", 'J', 1, 10, 5, 0, 5},
    {GnssSystem::kGlonass, "GLONASS", 'R', 1, 32, 6, 0, 2},
    {GnssSystem::kNavic, "NavIC", 'I', 1, 14, 7, 0, 6},
}};

constexpr const GnssSystemInfo& system_info(GnssSystem s) {
  return kGnssSystems[static_cast<std::size_t>(s)];
}

// Sets of systems (the ones a receiver tracks) as bit masks of GnssSystem values.
constexpr std::uint32_t system_bit(GnssSystem s) { return 1u << static_cast<unsigned>(s); }

// The NMEA satellite ID numberings u-blox receivers send (appendix A "Satellite numbering"
// above): NMEA 4.10 "extended", where the ID alone tells the system (GPS 1-32, SBAS 33-64 and
// 152-158, GLONASS 65-96, QZSS 193-202, Galileo 301-336, BeiDou 401-463), and NMEA 4.11, where
// the system ID does (Galileo 1-36, BeiDou 1-63, QZSS 1-10, NavIC 1-14; GPS, SBAS and GLONASS
// as in 4.10).
enum class NmeaNumbering { kV410Extended, kV411 };

class SatId {
 public:
  constexpr SatId() = default;
  // `number` in 0..255 (0: no satellite).
  constexpr SatId(GnssSystem system, int number)
      : system_(system), number_(static_cast<std::uint8_t>(number)) {}

  constexpr GnssSystem system() const { return system_; }
  constexpr int number() const { return number_; }
  constexpr const GnssSystemInfo& info() const { return system_info(system_); }
  // A number the system defines (what per-satellite tables hold).
  constexpr bool defined() const {
    return number_ >= info().first_number && number_ <= info().last_number;
  }

  // "G07" (RINEX 3.05 section 3.5; numbers 1-99).
  std::string rinex() const;
  // The satellite a RINEX system letter and number name, if the letter is one of the seven
  // systems' and the number is in 1-99.
  static std::optional<SatId> from_rinex(char letter, int number);

  constexpr std::uint8_t ubx_gnss_id() const { return info().ubx_gnss_id; }
  constexpr std::uint8_t ubx_sv_id() const {
    return static_cast<std::uint8_t>(number_ + info().ubx_sv_offset);
  }
  static std::optional<SatId> from_ubx(int gnss_id, int sv_id);
  // The single-number svId of UBX messages without a gnssId (NAV-SVINFO; appendix A above,
  // "UBX svId"): GPS 1-32, SBAS 120-158, Galileo 211-246, BeiDou 159-163 (PRN 1-5) and 33-64
  // (PRN 6-37), QZSS 193-202, GLONASS 65-96; none for NavIC and beyond those ranges. GPS PRNs
  // above 32 are sent as their PRN.
  std::optional<int> ubx_legacy_sv_id() const;

  // The NMEA satellite ID, if the numbering gives this satellite one. GPS PRNs above 32, which
  // neither numbering defines, are sent as their PRN.
  std::optional<int> nmea_id(NmeaNumbering numbering) const;

  // A stable index for the satellite's random streams (models/random.hpp stream_id): the GPS
  // PRN for GPS, 100 x the system's place in GnssSystem plus the number for the others. Never
  // changes, so seeds stay meaningful.
  constexpr int stream_index() const { return 100 * static_cast<int>(system_) + number_; }

  friend constexpr auto operator<=>(const SatId&, const SatId&) = default;

 private:
  GnssSystem system_ = GnssSystem::kGps;
  std::uint8_t number_ = 0;
};

constexpr SatId gps_sat(int prn) { return SatId(GnssSystem::kGps, prn); }

}  // namespace navemu
