#!/usr/bin/env bash
# Makes the files of the secure mode (docs/security.md) into a data folder, with openssl only:
#   DIR/ca.crt, ca.key                   private CA: signs every identity, the broker and robot certificates
#   DIR/permissions-ca.crt, .key         signs the DDS governance and permissions documents (S/MIME)
#   DIR/governance.xml, .p7s             DDS Security rules of the domain (authenticated, encrypted)
#   DIR/broker.crt, broker.key           the MQTT broker's TLS certificate
#   DIR/identities/NAME.crt, NAME.key    one DDS identity per service and operator tool
#   DIR/identities/NAME.permissions.xml, .p7s   what NAME may publish and subscribe (from the rules)
#   DIR/robots/ID.crt, ID.key            optional MQTT client certificates (`robot ID`)
# Certificates and keys are made once (existing ones are kept); the permissions are signed again on
# every run from compose/security/permissions.rules, so a changed rule applies at the next start.
set -euo pipefail

RULES=${SLAM_SECURITY_RULES:-$(dirname "$0")/security/permissions.rules}
DAYS=${SLAM_SECURITY_DAYS:-365}

usage() {
  cat <<USAGE
usage: compose/make-security.sh DIR                  CA, broker, every identity of the rules file
       compose/make-security.sh DIR operator NAME    one more operator identity (role operator)
       compose/make-security.sh DIR robot ID         an MQTT client certificate for robot ID
Environment: SLAM_SECURITY_DAYS (validity of what is made, days) [$DAYS];
  SLAM_BROKER_NAMES: more DNS names or IP addresses of the broker (space-separated; 127.0.0.1,
  localhost and this host's name are always in its certificate); SLAM_SECURITY_RULES [$RULES].
USAGE
}

fail() {
  echo "make-security: $1" >&2
  exit 2
}

(($# >= 1)) || { usage >&2; exit 2; }
[ "$1" = -h ] || [ "$1" = --help ] && { usage; exit 0; }
DIR=$1
shift
[ -r "$RULES" ] || fail "cannot read the rules file $RULES"
command -v openssl >/dev/null || fail "openssl is not installed (apt-get install openssl)"
umask 077
mkdir -p "$DIR/identities" "$DIR/robots" || fail "cannot create $DIR"

quiet() {  # quiet CMD...: runs CMD, shows its output only when it fails
  local out
  out=$("$@" 2>&1) || { echo "$out" >&2; fail "failed: $*"; }
}

new_key() { quiet openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$1"; }

# digitalSignature: the permissions CA signs the S/MIME documents itself (the S/MIME purpose check).
self_signed_ca() {  # self_signed_ca BASE CN
  [ -s "$1.crt" ] && return 0
  new_key "$1.key"
  quiet openssl req -x509 -new -key "$1.key" -out "$1.crt" -days "$DAYS" -subj "/CN=$2" \
    -addext "basicConstraints=critical,CA:TRUE" \
    -addext "keyUsage=critical,digitalSignature,keyCertSign,cRLSign"
  echo "make-security: made $1.crt"
}

signed_certificate() {  # signed_certificate BASE CN EXTENSIONS: a key and a certificate signed by ca.crt
  [ -s "$1.crt" ] && return 0
  new_key "$1.key"
  quiet openssl req -new -key "$1.key" -out "$1.csr" -subj "/CN=$2"
  printf 'basicConstraints=critical,CA:FALSE\n%s\n' "$3" >"$1.ext"
  quiet openssl x509 -req -in "$1.csr" -CA "$DIR/ca.crt" -CAkey "$DIR/ca.key" -set_serial "0x$(openssl rand -hex 16)" \
    -out "$1.crt" -days "$DAYS" -extfile "$1.ext"
  rm -f "$1.csr" "$1.ext"
  echo "make-security: made $1.crt"
}

smime_sign() {  # smime_sign XML P7S: signed by the permissions CA, as DDS Security reads it
  quiet openssl smime -sign -text -in "$1" -out "$2" -signer "$DIR/permissions-ca.crt" -inkey "$DIR/permissions-ca.key"
}

# Roles of every identity: the rules file's `role` lines, then DIR/identities/NAME.roles (operator ...).
identity_roles() {
  awk '$1 == "role" { print $2, $3 }' "$RULES"
  for f in "$DIR"/identities/*.roles; do
    [ -e "$f" ] && echo "$(basename "$f" .roles) $(cat "$f")"
  done
}

# topic_list KIND ROLES: the topics whose writers (KIND=w) or readers (KIND=r) include one of ROLES.
topic_list() {
  awk -v kind="$1" -v roles="$2" '
    BEGIN { n = split(roles, mine, ",") }
    $1 == "topic" {
      allowed = (kind == "w") ? $3 : $4
      if (allowed == "*") { print $2; next }
      m = split(allowed, who, ",")
      for (i = 1; i <= m; i++) for (j = 1; j <= n; j++) if (who[i] == mine[j]) { print $2; next }
    }' "$RULES"
}

topics_xml() {  # topics_xml ELEMENT TOPIC...: <publish> or <subscribe> with its topics, nothing if none
  local element=$1
  shift
  (($#)) || return 0
  echo "        <$element><topics>"
  for t in "$@"; do echo "          <topic>$t</topic>"; done
  echo "        </topics></$element>"
}

permissions() {  # permissions NAME ROLES: DIR/identities/NAME.permissions.xml and .p7s
  local name=$1 roles=$2 base="$DIR/identities/$1"
  local from until
  from=$(date -u -d "-1 day" +%Y-%m-%dT%H:%M:%S)  # a day early: hosts whose clocks differ
  until=$(date -u -d "+$DAYS days" +%Y-%m-%dT%H:%M:%S)
  mapfile -t writes < <(topic_list w "$roles")
  mapfile -t reads < <(topic_list r "$roles")
  {
    echo '<?xml version="1.0" encoding="UTF-8"?>'
    echo '<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">'
    echo '  <permissions>'
    echo "    <grant name=\"$name\">"
    echo "      <subject_name>CN=$name</subject_name>"
    echo "      <validity><not_before>$from</not_before><not_after>$until</not_after></validity>"
    echo '      <allow_rule>'
    echo '        <domains><id_range><min>0</min><max>232</max></id_range></domains>'
    topics_xml publish "${writes[@]}"
    topics_xml subscribe "${reads[@]}"
    echo '      </allow_rule>'
    echo '      <default>DENY</default>'
    echo '    </grant>'
    echo '  </permissions>'
    echo '</dds>'
  } >"$base.permissions.xml"
  smime_sign "$base.permissions.xml" "$base.permissions.p7s"
}

# Every participant authenticated; discovery and liveliness encrypted; every sample's payload
# encrypted (data protection: no robot id or coordinate readable on the wire; Fast DDS sends no key
# in clear beside it); each topic's readers and writers checked against the permissions. Not
# rtps protection (whole messages): Fast DDS 2.9 then overruns its message buffer under load and
# aborts; not metadata protection: it halves the gateway's rate (docs/security.md, performance.md).
governance() {
  cat >"$DIR/governance.xml" <<'XML'
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>0</min><max>232</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>NONE</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
XML
  smime_sign "$DIR/governance.xml" "$DIR/governance.p7s"
}

valid_name() { [[ $1 =~ ^[A-Za-z0-9][A-Za-z0-9_.-]*$ ]] || fail "'$1' is not a valid name (letters, digits, _ . -)"; }

self_signed_ca "$DIR/ca" "slamfleet CA"
self_signed_ca "$DIR/permissions-ca" "slamfleet permissions CA"

case "${1:-}" in
  "") ;;
  operator)
    (($# == 2)) || fail "usage: make-security.sh DIR operator NAME"
    valid_name "$2"
    echo operator >"$DIR/identities/$2.roles"
    ;;
  robot)
    (($# == 2)) || fail "usage: make-security.sh DIR robot ID"
    valid_name "$2"
    signed_certificate "$DIR/robots/$2" "$2" "extendedKeyUsage=clientAuth"
    exit 0
    ;;
  *) fail "unknown command '$1' (see --help)" ;;
esac

broker_names="IP:127.0.0.1,DNS:localhost,DNS:$(hostname)"
for n in ${SLAM_BROKER_NAMES:-}; do
  if [[ $n =~ ^[0-9.]+$ || $n == *:* ]]; then broker_names+=",IP:$n"; else broker_names+=",DNS:$n"; fi
done
signed_certificate "$DIR/broker" "slamfleet broker" "subjectAltName=$broker_names
extendedKeyUsage=serverAuth"

governance
while read -r name roles; do
  valid_name "$name"
  signed_certificate "$DIR/identities/$name" "$name" "keyUsage=critical,digitalSignature"
  permissions "$name" "$roles"
done < <(identity_roles)
echo "make-security: governance and permissions signed in $DIR"
