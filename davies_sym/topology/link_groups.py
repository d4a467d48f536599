"""Union-find of links: links sharing one gear axis (layout), or joined into one rigid
member by a brake or a clutch (operating states)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence


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


def link_roots(links: Sequence[str], joined: Iterable[tuple[str, str]]) -> dict[str, str]:
    """Each of ``links`` -> the root of its group once the pairs ``joined`` are joined in
    their order (of each pair, the second link's root stays): the groups as one value."""
    groups = LinkGroups(links)
    for a, b in joined:
        groups.union(a, b)
    return {link: groups.find(link) for link in links}


def link_classes(links: Sequence[str], joined: Iterable[tuple[str, str]]) -> dict[str, str]:
    """Each of ``links`` -> the first link (in name order) of its class, the classes that
    the pairs ``joined`` make (links sharing one gear axis)."""
    roots = link_roots(links, joined)
    first: dict[str, str] = {}
    for link in sorted(links):
        first.setdefault(roots[link], link)
    return {link: first[roots[link]] for link in links}
