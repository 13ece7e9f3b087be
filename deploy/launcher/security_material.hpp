#pragma once
/// @file
/// `security: on`: what the launcher makes for a secured run. A run CA (EC P-256,
/// the identity and the permissions CA), and per participant (the clock, every service
/// instance, climbsim-clockctl) a certificate with subject CN=<name> and a permissions
/// document that grants exactly the topics of its program (climbsim/program_topics.hpp), all
/// signed by the CA (S/MIME, `openssl smime -sign`); a governance document that refuses
/// unauthenticated participants, encrypts discovery, signs every RTPS message and encrypts the
/// data of the topics that must stay secret (the threat model: docs/security.md). The CA's key
/// is deleted once everything is signed: nobody can mint another identity for the run. Keys are
/// 0600 in a 0700 directory.

#include <map>
#include <string>
#include <vector>

#include "compose_file.hpp"

namespace climbsim::launcher {

/// Sub-directory of the run directory that holds the security files.
inline constexpr const char* kSecurityDirName = "security";

/// One participant's grant.
struct SecurityGrant {
  std::string identity;             ///< the DDS participant name (certificate CN, sub-directory)
  std::string host = kLocalHost;    ///< the host it runs on (what is copied where)
  std::vector<std::string> writes;  ///< topics it may publish
  std::vector<std::string> reads;   ///< topics it may subscribe to
};

/// The grants of a run of `compose`: the clock, each service instance, climbsim-clockctl.
/// Throws ConfigError "<compose>:<line>: services.<name>: ..." for a service whose program has
/// no topic table (a Python or C client, or a program of your own): nobody could tell which
/// topics to grant it.
std::vector<SecurityGrant> securityGrants(const ComposeFile& compose);

/// How the samples of the topics a governance rule names cross the network.
struct TopicProtection {
  std::string expression;  ///< topic name expression of the rule (fnmatch: `clock/*`, `*`)
  std::string data;        ///< data_protection_kind: ENCRYPT (secret and authentic) or NONE
  std::string why;         ///< the threat it answers (docs/security.md#per-topic-protection)
};

/// The governance's topic rules, first match wins: the clock's control plane and the record
/// batches encrypted, the step data in the clear. Every RTPS message of the run is signed
/// besides (rtps_protection_kind SIGN), so every topic's samples are authentic.
const std::vector<TopicProtection>& topicProtections();

/// The data protection of `topic`: the first rule of topicProtections() whose expression
/// matches it.
const TopicProtection& protectionOf(const std::string& topic);

/// The governance document for domain `domain_id` (XML, unsigned).
std::string governanceXml(int domain_id);

/// The permissions document of `grant` on domain `domain_id` (XML, unsigned), valid for `days`.
std::string permissionsXml(const SecurityGrant& grant, int domain_id, int days);

/// Makes the run CA and every grant's files in `dir` (created 0700; what was there goes) with
/// the `openssl` program found on `path_env`. Throws std::runtime_error naming the openssl
/// command that failed and its output. Then checks every grant's files as the services will
/// (climbsim/security_files.hpp).
void makeSecurityMaterial(const std::string& dir, int domain_id, const std::vector<SecurityGrant>& grants,
                          const std::string& path_env);

/// Copies to each ssh host of `compose` the files its processes need (the CA certificate, the
/// governance and their own identities, never another host's keys) into the same path `dir`,
/// through `ssh ... 'tar -x'` (never removing what is there: the host may share this machine's files). Throws std::runtime_error naming the host if a copy fails.
void copySecurityMaterial(const ComposeFile& compose, const std::string& dir, const std::vector<SecurityGrant>& grants);

/// The environment a process of identity `identity` needs to load its files from `dir`.
std::map<std::string, std::string> securityEnvironment(const std::string& dir, const std::string& identity);

}  // namespace climbsim::launcher
