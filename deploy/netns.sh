#!/usr/bin/env bash
# Two test hosts on one machine: network namespaces NAME-base (base station, 10.NET.0.1)
# and NAME-robot (robot, 10.NET.0.2) joined by a veth pair NAME-b <-> NAME-r, with loopback
# up, no route but the link's own /24 (so no multicast route), multicast off on the link,
# and every multicast datagram dropped in and out by an nftables rule on both hosts (a
# sender that names its interface passes the routing table; the rule stops it too). Needs
# root (ip netns) and nft (Debian's nftables).
#
#   deploy/netns.sh up NAME NET [multicast]   create (removes leftovers of the same NAME
#                                    first); with `multicast`, one LAN where multicast works
#                                    (a route for 224.0.0.0/4 on the link, no drop rule)
#   deploy/netns.sh down NAME        remove both namespaces (and so the link)
#   deploy/netns.sh cut NAME         take the link down (both ends)
#   deploy/netns.sh restore NAME     bring it up again
#   deploy/netns.sh exec NAME base|robot CMD...   run CMD on one host
#
# NAME: at most 12 characters (interface names are limited to 15). NET: 0-255.
set -euo pipefail

usage() { echo "usage: $0 up NAME NET [multicast] | down NAME | cut NAME | restore NAME | exec NAME base|robot CMD..." >&2; exit 2; }
[ $# -ge 2 ] || usage
verb=$1 name=$2
[ ${#name} -le 12 ] || { echo "$0: NAME '$name' is longer than 12 characters" >&2; exit 2; }
base="$name-base" robot="$name-robot" vb="$name-b" vr="$name-r"

down() {
  ip netns del "$base" 2>/dev/null || true
  ip netns del "$robot" 2>/dev/null || true
  ip link del "$vb" 2>/dev/null || true
}

case "$verb" in
  up)
    [ $# -eq 3 ] || { [ $# -eq 4 ] && [ "$4" = multicast ]; } || usage
    net=$3 multicast=${4:-}
    command -v nft > /dev/null || { echo "$0: nft not found (apt-get install nftables)" >&2; exit 2; }
    [[ "$net" =~ ^[0-9]+$ ]] && [ "$net" -le 255 ] || { echo "$0: NET '$net' is not 0-255" >&2; exit 2; }
    down
    ip netns add "$base"
    ip netns add "$robot"
    ip link add "$vb" type veth peer name "$vr"
    ip link set "$vb" netns "$base"
    ip link set "$vr" netns "$robot"
    ip -n "$base" addr add "10.$net.0.1/24" dev "$vb"
    ip -n "$robot" addr add "10.$net.0.2/24" dev "$vr"
    for ns_if in "$base:$vb" "$robot:$vr"; do
      ns=${ns_if%%:*} if=${ns_if##*:}
      ip -n "$ns" link set lo up
      if [ -n "$multicast" ]; then
        ip -n "$ns" link set "$if" multicast on
        ip -n "$ns" link set "$if" up
        ip -n "$ns" route add 224.0.0.0/4 dev "$if"
        continue
      fi
      ip -n "$ns" link set "$if" multicast off
      ip -n "$ns" link set "$if" up
      ip netns exec "$ns" nft -f - <<'NFT'
table inet stickrep_no_multicast {
  chain out { type filter hook output priority 0; ip daddr 224.0.0.0/4 drop; }
  chain in { type filter hook input priority 0; ip daddr 224.0.0.0/4 drop; }
}
NFT
    done
    lan="no multicast"
    [ -z "$multicast" ] || lan="multicast on the link"
    echo "base station 10.$net.0.1 in netns $base, robot 10.$net.0.2 in netns $robot; $lan"
    ;;
  down) down ;;
  cut)
    ip -n "$robot" link set "$vr" down
    ip -n "$base" link set "$vb" down
    ;;
  restore)
    ip -n "$robot" link set "$vr" up
    ip -n "$base" link set "$vb" up
    ;;
  exec)
    [ $# -ge 4 ] || usage
    host=$3; shift 3
    case "$host" in base) ns=$base ;; robot) ns=$robot ;; *) usage ;; esac
    exec ip netns exec "$ns" "$@"
    ;;
  *) usage ;;
esac
