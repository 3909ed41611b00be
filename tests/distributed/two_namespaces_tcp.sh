#!/bin/bash
# two_namespaces_tcp.sh — frontsteal-mpi with its two ranks in two Linux network namespaces joined by a veth
# pair (addresses of its own, 10.218.<pid-derived>.1/.2, no other network), launched by mpirun through an rsh
# agent that enters the second namespace, with shared-memory transports off (--mca btl tcp,self, osc pt2pt) so
# every byte between the ranks crosses TCP. --bind-to none: each namespace's daemon believes it has the whole
# machine and binds its first rank to core 0, so by default both ranks shared one core (every operation then
# waited for the other process to be scheduled: a steal measured 2.7 ms bound, 1.2 ms unbound). The namespaces, the veth pair and the agent are removed by a trap,
# on success, failure or interruption. Needs root and ip(8); otherwise exits 77 (ctest: skipped).
#   [NS_RANKS=A,B] [NS_OSC=pt2pt|ucx] two_namespaces_tcp.sh MPIEXEC FRONTSTEAL_MPI [program arguments...]
# NS_RANKS: ranks in the first and the second namespace (default 1,1); ranks in one namespace talk TCP too.
# NS_OSC: the one-sided component (default pt2pt). ucx: osc/ucx over UCX's TCP transport (UCX_TLS=tcp,self; Open
# MPI 4.1 offers osc/ucx only for InfiniBand-style devices unless told "any"), which accepts
# MPI_THREAD_MULTIPLE, so --progress-thread can run; two-sided traffic stays on btl/tcp either way.
set -u
mpiexec=$1; prog=$2; shift 2
ns_ranks=${NS_RANKS:-1,1}
ranks_a=${ns_ranks%%,*}; ranks_b=${ns_ranks##*,}
ranks_a=${ranks_a:-1}; ranks_b=${ranks_b:-1}
case "$ranks_a$ranks_b" in *[!0-9]*) echo "two_namespaces_tcp: NS_RANKS must be A,B (counts)"; exit 2 ;; esac
case "${NS_OSC:-pt2pt}" in
  pt2pt) osc_args=(--mca osc pt2pt) ;;
  ucx) osc_args=(--mca osc ucx --mca osc_ucx_tls any --mca osc_ucx_devices any -x UCX_TLS=tcp,self
                 -x UCX_WARN_UNUSED_ENV_VARS=n) ;;
  *) echo "two_namespaces_tcp: NS_OSC must be pt2pt or ucx"; exit 2 ;;
esac
[ "$(id -u)" -eq 0 ] && command -v ip > /dev/null || { echo "two_namespaces_tcp: needs root and ip(8): skipped"; exit 77; }
tag=fs$$
a=${tag}a; b=${tag}b
net=10.218.$(( $$ % 250 + 1 ))
agent=$(mktemp -t ${tag}-agent.XXXXXX)
cleanup() {
  ip netns del "$a" 2> /dev/null
  ip netns del "$b" 2> /dev/null  # deleting a namespace removes its end of the veth pair, and so the pair
  rm -f "$agent"
}
trap cleanup EXIT INT TERM
ip netns add "$a" && ip netns add "$b" || { echo "two_namespaces_tcp: cannot create namespaces: skipped"; exit 77; }
ip link add ${tag}va type veth peer name ${tag}vb || exit 1
ip link set ${tag}va netns "$a" && ip link set ${tag}vb netns "$b" || exit 1
ip -n "$a" addr add $net.1/24 dev ${tag}va && ip -n "$b" addr add $net.2/24 dev ${tag}vb || exit 1
for ns in "$a" "$b"; do ip -n "$ns" link set lo up; done
ip -n "$a" link set ${tag}va up && ip -n "$b" link set ${tag}vb up || exit 1
printf '#!/bin/sh\n# rsh agent: "host command..." runs the command in namespace %s\nshift\nexec ip netns exec %s sh -c "$*"\n' "$b" "$b" > "$agent"
chmod +x "$agent"
echo "two_namespaces_tcp: ranks 0..$((ranks_a - 1)) in $a ($net.1), ranks $ranks_a..$((ranks_a + ranks_b - 1)) in $b ($net.2), TCP only, osc ${NS_OSC:-pt2pt}"
ip netns exec "$a" "$mpiexec" --host "$(hostname):$ranks_a,$b:$ranks_b" -np $((ranks_a + ranks_b)) --mca plm_rsh_agent "$agent" \
  --mca oob_tcp_if_include $net.0/24 --mca btl_tcp_if_include $net.0/24 --mca btl tcp,self --mca pml ob1 \
  "${osc_args[@]}" --mca mpi_yield_when_idle 1 --bind-to none "$prog" "$@"
