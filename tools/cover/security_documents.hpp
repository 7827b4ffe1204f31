#pragma once

#include <string>

#include "cover/dds/access_rules.hpp"

namespace cover::cli {

// The DDS-Security XML documents of a fleet, before signing (OMG DDS-Security 1.1 schema,
// element order as Fast DDS 2.9's parser requires).

// Every domain 0..max_domain: no unauthenticated participant, join access control, every
// topic read/write access controlled, discovery, liveliness and data encrypted.
std::string governance_xml(int max_domain);

// One grant: `subject` (RFC 2253) may publish and subscribe exactly `access` on domains
// 0..max_domain between the two UTC times ("YYYY-MM-DDTHH:MM:SS"); everything else denied.
std::string permissions_xml(const std::string& grant_name, const std::string& subject,
                            const std::string& not_before_utc, const std::string& not_after_utc,
                            const dds::TopicAccess& access, int max_domain);

}  // namespace cover::cli
