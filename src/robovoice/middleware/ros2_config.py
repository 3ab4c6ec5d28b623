"""`ros2://` URIs and the ROS 2 settings they stand for (see docs/ros2.md).

    ros2://                                   domain 0, discovery on this machine only
    ros2://?domain_id=42                      ROS_DOMAIN_ID 42
    ros2://?domain_id=42&manifests=DIR        the manifest folder binding tools to ROS 2 interfaces
    ros2://?domain_id=42&discovery=subnet     open discovery to the network (robot + edge server)

Parameters: ``domain_id`` (0..232, default 0), ``discovery`` (``localhost``, the default: no
discovery traffic leaves the machine; ``subnet``: multicast on the local network; ``off``),
``peers`` (static peers for discovery, host names or addresses, comma-separated; needs
``discovery`` other than localhost to reach other machines), ``manifests`` (a folder of
manifests with `ros2` blocks), ``lease`` (seconds a dead participant of *this* process stays
in others' graphs, default 2; 0 keeps Fast DDS's own default of 20 s and any profile file).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Literal
from urllib.parse import parse_qs

from robovoice.errors import ConfigError
from robovoice.urls import split_uri

Discovery = Literal["localhost", "subnet", "off"]
_KNOWN = ("discovery", "domain_id", "lease", "manifests", "peers")
MAX_DOMAIN_ID = 232
"""Fast DDS fails above 232 (its port arithmetic)."""
DEFAULT_LEASE_S = 2.0


@dataclass(frozen=True, slots=True)
class Ros2Settings:
    """What a `ros2://` URI says, checked."""

    uri: str
    domain_id: int = 0
    discovery: Discovery = "localhost"
    peers: tuple[str, ...] = ()
    manifests: Path | None = None
    lease_s: float = DEFAULT_LEASE_S

    @classmethod
    def from_uri(cls, uri: str) -> Ros2Settings:
        parts = split_uri(uri, "ros2 URI")
        if parts.scheme != "ros2":
            raise ConfigError(f"not a ros2:// URI: {uri!r}")
        if parts.netloc or parts.path not in ("", "/"):
            raise ConfigError(f"{uri}: a ros2:// URI has no host or path; write ros2://?domain_id=N")
        query = parse_qs(parts.query, keep_blank_values=True)
        unknown = sorted(set(query) - set(_KNOWN))
        if unknown:
            raise ConfigError(f"{uri}: unknown parameter(s) {', '.join(unknown)}; known: {', '.join(_KNOWN)}")
        for name, values in query.items():
            if len(values) > 1:
                raise ConfigError(f"{uri}: parameter {name!r} given {len(values)} times")
        one = {name: values[0] for name, values in query.items()}
        domain = _integer(uri, "domain_id", one.get("domain_id", "0"))
        if not 0 <= domain <= MAX_DOMAIN_ID:
            raise ConfigError(f"{uri}: domain_id must be 0..{MAX_DOMAIN_ID}, not {domain}")
        discovery = one.get("discovery", "localhost")
        if discovery not in ("localhost", "subnet", "off"):
            raise ConfigError(f"{uri}: discovery must be localhost, subnet or off, not {discovery!r}")
        peers = tuple(p.strip() for p in one.get("peers", "").split(",") if p.strip())
        manifests = Path(one["manifests"]) if one.get("manifests") else None
        try:
            lease = float(one.get("lease", str(DEFAULT_LEASE_S)))
        except ValueError:
            raise ConfigError(f"{uri}: lease must be a number of seconds") from None
        if not math.isfinite(lease) or lease < 0:
            raise ConfigError(f"{uri}: lease must be a number of seconds ≥ 0")
        return cls(uri, domain, discovery, peers, manifests, lease)  # type: ignore[arg-type]  # checked above

    def environment(self) -> dict[str, str]:
        """The ROS 2 environment variables these settings stand for (read by rcl at init)."""
        env = {
            "ROS_DOMAIN_ID": str(self.domain_id),
            "ROS_AUTOMATIC_DISCOVERY_RANGE": {"localhost": "LOCALHOST", "subnet": "SUBNET", "off": "OFF"}[
                self.discovery
            ],
        }
        env["ROS_STATIC_PEERS"] = ";".join(self.peers)
        return env


def _integer(uri: str, name: str, text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise ConfigError(f"{uri}: {name} must be an integer, not {text!r}") from None


def fastdds_profile(lease_s: float) -> str:
    """A Fast DDS XML profile whose participants are declared dead `lease_s` after their last
    announcement (Fast DDS's default is 20 s): a `kill -9`'d node leaves the graph in ~lease_s."""
    sec = int(lease_s)
    nanosec = round((lease_s - sec) * 1e9)
    announce = max(lease_s / 4.0, 0.1)
    a_sec, a_nsec = int(announce), round((announce - int(announce)) * 1e9)
    return f"""<?xml version="1.0" encoding="UTF-8" ?>
<dds xmlns="http://www.eprosima.com">
  <profiles>
    <participant profile_name="robovoice_short_lease" is_default_profile="true">
      <rtps>
        <builtin>
          <discovery_config>
            <leaseDuration><sec>{sec}</sec><nanosec>{nanosec}</nanosec></leaseDuration>
            <leaseAnnouncement><sec>{a_sec}</sec><nanosec>{a_nsec}</nanosec></leaseAnnouncement>
          </discovery_config>
        </builtin>
      </rtps>
    </participant>
  </profiles>
</dds>
"""
