"""Union-find of links: links sharing one gear axis (layout), or joined into one rigid
member by a brake or a clutch (operating states)."""

from __future__ import annotations

from collections.abc import Sequence


class LinkGroups:
    """Union-find of links: links sharing one gear axis (layout), or joined into one
    rigid member by a brake or a clutch (operating states)."""

    def __init__(self, links: Sequence[str]):
        self.parent = {link: link for link in links}

    def find(self, link: str) -> str:
        while self.parent[link] != link:
            self.parent[link] = self.parent[self.parent[link]]
            link = self.parent[link]
        return link

    def union(self, a: str, b: str) -> None:
        """Join the groups of ``a`` and ``b``; ``b``'s representative stays."""
        self.parent[self.find(a)] = self.find(b)
