#!/usr/bin/env bash
# Makes everything a secured StickRep deployment needs (DDS Security with Fast DDS's built-in
# plugins: PKI-DH authentication, Access-Permissions access control, AES-GCM-GMAC crypto)
# into one directory that stays OUT of git (it holds private keys):
#
#   DIR/identity_ca.cert.pem       the identity CA every participant trusts
#   DIR/permissions_ca.cert.pem    the permissions CA that signs governance and permissions
#   DIR/governance.p7s             the domain governance (governance.xml, S/MIME-signed)
#   DIR/governance_discovery_server.p7s   the same for a deployment with a discovery server
#                                  (endpoint discovery and liveliness not encrypted: Fast DDS
#                                  2.9's server cannot relay them encrypted)
#   DIR/NAME/cert.pem, key.pem     one ECDSA P-256 identity per process, the console, the
#                                  discovery server and the transport bench
#   DIR/NAME/permissions.p7s       what NAME may publish and subscribe (deny by default)
#   DIR/discovery_server.xml       the Fast DDS profile fast-discovery-server runs with
#   DIR/private/                   the two CAs' keys (to sign more later); keep them apart
#
#   deploy/security/make-keys.sh DIR [--days N]
#
# The policy (docs/security.md): no unauthenticated participant joins; discovery and
# liveliness are encrypted (with simple discovery); commands (robot/motion/command, device/base/wheel_command),
# goals (mission/goal) and camera frames (device/camera/frame, robot/camera/image) are
# encrypted; every topic's readers and writers are access-controlled; only the executive and
# the console may write mission/goal, only the executive robot/motion/command, only
# locomotion device/base/wheel_command. Needs openssl. Exit code 2 for a bad command line.
set -euo pipefail
set -f  # topic expressions such as * are not file names

usage() { echo "usage: $0 DIR [--days N]" >&2; exit 2; }
[ $# -ge 1 ] || usage
out=$1; shift
days=3650
while [ $# -gt 0 ]; do
  case "$1" in
    --days) [ $# -ge 2 ] && [[ "$2" =~ ^[0-9]+$ ]] || usage; days=$2; shift 2 ;;
    *) usage ;;
  esac
done
command -v openssl > /dev/null || { echo "$0: openssl not found (apt-get install openssl)" >&2; exit 2; }
mkdir -p "$out/private"
chmod 700 "$out/private"
out=$(cd "$out" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

org="StickRep"

# A private key on the P-256 curve (PKCS#8 PEM).
new_key() { openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$1" 2> /dev/null; chmod 600 "$1"; }

# A self-signed CA certificate: new_ca NAME COMMON_NAME
new_ca() {
  new_key "$out/private/$1.key.pem"
  openssl req -new -x509 -sha256 -days "$days" -key "$out/private/$1.key.pem" \
    -subj "/C=US/O=$org/CN=$2" -addext "basicConstraints=critical,CA:TRUE" \
    -addext "keyUsage=critical,digitalSignature,keyCertSign,cRLSign" -out "$out/$1.cert.pem"
}

# An identity certificate signed by the identity CA: new_identity NAME
new_identity() {
  mkdir -p "$out/$1"
  new_key "$out/$1/key.pem"
  openssl req -new -sha256 -key "$out/$1/key.pem" -subj "/C=US/O=$org/CN=$1" -out "$work/$1.csr"
  printf 'basicConstraints=critical,CA:FALSE\nkeyUsage=critical,digitalSignature,keyAgreement\n' > "$work/id.ext"
  openssl x509 -req -sha256 -days "$days" -in "$work/$1.csr" -CA "$out/identity_ca.cert.pem" \
    -CAkey "$out/private/identity_ca.key.pem" -CAcreateserial -CAserial "$out/private/identity_ca.srl" \
    -extfile "$work/id.ext" -out "$out/$1/cert.pem" 2> /dev/null
}

# S/MIME-signs FILE.xml with the permissions CA into OUT.p7s: sign XML OUT
sign() {
  openssl smime -sign -text -in "$1" -out "$2" -signer "$out/permissions_ca.cert.pem" \
    -inkey "$out/private/permissions_ca.key.pem"
}

# <topic> lines for a list of topic names.
topics() { for t in "$@"; do printf '            <topic>%s</topic>\n' "$t"; done; }

# The permissions of one identity: permissions NAME "PUBLISHED TOPICS" "SUBSCRIBED TOPICS"
permissions() {
  local name=$1 pub=$2 sub=$3
  {
    cat <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_permissions.xsd">
  <permissions>
    <grant name="stickrep_$name">
      <subject_name>CN=$name,O=$org,C=US</subject_name>
      <validity>
        <not_before>$(date -u +%Y-%m-%dT00:00:00)</not_before>
        <not_after>$(date -u -d "+$days days" +%Y-%m-%dT00:00:00)</not_after>
      </validity>
      <allow_rule>
        <domains><id_range><min>0</min><max>232</max></id_range></domains>
XML
    if [ -n "$pub" ]; then
      echo "        <publish>"; echo "          <topics>"; topics $pub; echo "          </topics>"; echo "        </publish>"
    fi
    if [ -n "$sub" ]; then
      echo "        <subscribe>"; echo "          <topics>"; topics $sub; echo "          </topics>"; echo "        </subscribe>"
    fi
    cat <<XML
      </allow_rule>
      <default>DENY</default>
    </grant>
  </permissions>
</dds>
XML
  } > "$out/$name/permissions.xml"
  sign "$out/$name/permissions.xml" "$out/$name/permissions.p7s"
}

new_ca identity_ca "StickRep identity CA"
new_ca permissions_ca "StickRep permissions CA"

# Governance: the first topic rule whose expression matches a topic applies.
# rule EXPRESSION METADATA_PROTECTION DATA_PROTECTION DISCOVERY_AND_LIVELINESS_PROTECTED
rule() {
  cat <<XML
        <topic_rule>
          <topic_expression>$1</topic_expression>
          <enable_discovery_protection>$4</enable_discovery_protection>
          <enable_liveliness_protection>$4</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>$2</metadata_protection_kind>
          <data_protection_kind>$3</data_protection_kind>
        </topic_rule>
XML
}
# governance PROTECTED(true|false) > FILE: with PROTECTED, endpoint discovery and liveliness
# go over the encrypted built-in endpoints. Fast DDS 2.9's discovery server cannot relay
# those, so a deployment with a discovery server uses the other document: endpoints are then
# announced in the clear, but only to authenticated participants.
governance() {
  local liveliness=NONE
  [ "$1" = true ] && liveliness=ENCRYPT
  cat <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://www.omg.org/spec/DDS-SECURITY/20170901/omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>0</min><max>232</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>$liveliness</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
XML
  # Commands, goals and camera frames: payload encrypted, submessage signed. The transport
  # bench's ping/pong topics are protected the same way, so that it measures their cost.
  for t in robot/motion/command device/base/wheel_command mission/goal device/camera/frame \
           robot/camera/image "bench/*"; do
    rule "$t" SIGN ENCRYPT "$1"
  done
  # Every other topic: access-controlled and discovered only by authenticated peers, sent
  # in the clear (sensor streams, pose, status: no secret, and the cost would be paid at 20 Hz).
  rule "*" NONE NONE "$1"
  cat <<XML
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
XML
}
governance true > "$out/governance.xml"
sign "$out/governance.xml" "$out/governance.p7s"
governance false > "$out/governance_discovery_server.xml"
sign "$out/governance_discovery_server.xml" "$out/governance_discovery_server.p7s"

# Who publishes and subscribes what (README's process table); system/status is every
# process's heartbeat.
declare -A pub sub
pub[virtual_robot]="device/sonar/echo device/camera/frame device/base/encoders sim/ground_truth system/status"
sub[virtual_robot]="device/base/wheel_command localization/pose"
pub[sonar]="robot/sonar system/status"
sub[sonar]="device/sonar/echo"
pub[camera]="robot/camera/image system/status"
sub[camera]="device/camera/frame"
pub[locomotion]="device/base/wheel_command robot/odometry robot/motion/state system/status"
sub[locomotion]="robot/motion/command device/base/encoders robot/sonar"
pub[landmark]="perception/landmark system/status"
sub[landmark]="robot/camera/image robot/sonar robot/odometry"
pub[localizer]="localization/pose localization/hypotheses map/stickrep system/status"
sub[localizer]="perception/landmark robot/sonar robot/odometry"
pub[executive]="robot/motion/command mission/status mission/goal_result mission/goal system/status"
sub[executive]="robot/odometry system/status localization/pose robot/motion/state mission/goal"
# The operator's console reads every topic and sends goals.
pub[console]="mission/goal"
sub[console]="*"
# The discovery server relays discovery only: no topic of its own.
pub[discovery_server]=""
sub[discovery_server]="system/status"
# stickrep-transport-bench --security-dir: its ping and pong.
pub[bench]="bench/ping bench/pong"
sub[bench]="bench/ping bench/pong"

for name in virtual_robot sonar camera locomotion landmark localizer executive console \
            discovery_server bench; do
  new_identity "$name"
  permissions "$name" "${pub[$name]}" "${sub[$name]}"
done

# fast-discovery-server -x: the server's own identity (its -l and -p come from the graph).
# With -x the tool takes the GUID prefix from the file: the one of server id 0, which the
# clients (deploy/fastdds/discovery_client.xml, --discovery-server) expect.
cat > "$out/discovery_server.xml" <<XML
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <participant profile_name="stickrep_secure_server" is_default_profile="true">
      <rtps>
        <prefix>44.53.00.5f.45.50.52.4f.53.49.4d.41</prefix>
        <builtin>
          <discovery_config>
            <discoveryProtocol>SERVER</discoveryProtocol>
          </discovery_config>
        </builtin>
        <propertiesPolicy>
          <properties>
            <property><name>dds.sec.auth.plugin</name><value>builtin.PKI-DH</value></property>
            <property><name>dds.sec.auth.builtin.PKI-DH.identity_ca</name><value>file://$out/identity_ca.cert.pem</value></property>
            <property><name>dds.sec.auth.builtin.PKI-DH.identity_certificate</name><value>file://$out/discovery_server/cert.pem</value></property>
            <property><name>dds.sec.auth.builtin.PKI-DH.private_key</name><value>file://$out/discovery_server/key.pem</value></property>
            <property><name>dds.sec.access.plugin</name><value>builtin.Access-Permissions</value></property>
            <property><name>dds.sec.access.builtin.Access-Permissions.permissions_ca</name><value>file://$out/permissions_ca.cert.pem</value></property>
            <property><name>dds.sec.access.builtin.Access-Permissions.governance</name><value>file://$out/governance_discovery_server.p7s</value></property>
            <property><name>dds.sec.access.builtin.Access-Permissions.permissions</name><value>file://$out/discovery_server/permissions.p7s</value></property>
            <property><name>dds.sec.crypto.plugin</name><value>builtin.AES-GCM-GMAC</value></property>
          </properties>
        </propertiesPolicy>
      </rtps>
    </participant>
  </profiles>
</dds>
XML
echo "security material for StickRep in $out: 2 CAs, governance, 10 identities with their permissions"
