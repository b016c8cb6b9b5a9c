# Chapaev online: the interface in English.
# Every message here has a twin of the same id in ru.ftl (a unit test
# checks it). Numbers that count things go through selectors, so each
# language says its own plural forms.

## Shared words

app-title = Chapaev online
player-default-name = Player
sign-in = Sign in
sign-out = Sign out
cancel = Cancel
join = Join
watch = Watch
replay = Replay
lobby = Lobby
leaderboard = Leaderboard
how-to-play = How to play
rules-short = Rules
copy-key = Copy the key
key-copied = The key is copied: keep it safe
signed-out-because = signed out: { $reason }
side-white = White
side-black = Black
level-easy = easy
level-medium = medium
level-hard = hard
level-adaptive = adaptive
computer-level = computer ({ $level })
shots-count = { $count ->
    [one] 1 shot
   *[other] { $count } shots
}
rounds-count = { $count ->
    [one] 1 round
   *[other] { $count } rounds
}
games-count = { $count ->
    [one] 1 game
   *[other] { $count } games
}

## Lobby

lobby-your-name = Your name
lobby-signed-in = Signed in
lobby-rated-on = Rated: on
lobby-rated-off = Rated: off
lobby-return-title = Your match is still on
lobby-return-body = You left it while it was being played: return before you forfeit it.
lobby-return-yes = Return to it
lobby-return-no = Stay here
lobby-sign-out-title = Sign out?
lobby-sign-out-body = The key is the only way back into this account. Copy it and keep it somewhere safe first, or the account is lost.
lobby-tagline = flick your checkers, knock theirs off the board
lobby-tagline-short = flick yours, knock theirs off
lobby-quick-match = Quick match
lobby-computer-easy = Computer: easy
lobby-computer-medium = Computer: medium
lobby-computer-hard = Computer: hard
lobby-computer-adaptive = Computer: adaptive
lobby-friend = A friend (link)
lobby-sandbox = Physics sandbox
lobby-offline = Offline vs computer
lobby-offline-title = Play the computer offline
lobby-offline-body = Played in this page, with no server: casual, never rated, not kept. Choose the computer's level.
lobby-server-unreachable = No server: playing the computer offline.
lobby-join-by-id = Join by id
lobby-match-id = match id
lobby-footer-short = Writing a bot? See /api
lobby-footer = Writing a bot? The HTTP and WebSocket protocol is described at /api
lobby-none-yet = none yet
lobby-list-open = Waiting for an opponent
lobby-list-live = Being played
lobby-list-finished = Finished
lobby-creating = creating the match...
lobby-fact-rated = rated
lobby-fact-not-playable = not playable here
lobby-fact-white-won = White won
lobby-fact-black-won = Black won
lobby-fact-drawn = drawn
lobby-fact-waiting = waiting
lobby-versus = { $first } vs { $second }

## The shot log

shot-who-you = You
shot-nothing = { $who }: nothing fell
shot-knocked = { $who } knocked off { $taken ->
    [one] 1 piece
   *[other] { $taken } pieces
}
shot-lost = { $who } lost { $lost ->
    [one] 1 piece
   *[other] { $lost } pieces
}
shot-knocked-lost = { $who } knocked off { $taken ->
    [one] 1 piece
   *[other] { $taken } pieces
}, lost { $lost }
shot-then-match-over = the match is over
shot-then-you-won-round = you won the round
shot-then-side-won-round = { $side ->
    [white] White
   *[black] Black
} won the round
shot-then-round-drawn = the round is drawn
shot-then-you-again = shoot again
shot-then-again = shoots again
score-rounds-won = Rounds won: White { $white } · Black { $black }
score-rounds-drawn = drawn { $drawn }

## The end of a match

end-drawn = Drawn
end-you-won = You won!
end-you-lost = You lost
end-side-won = { $side ->
    [white] White
   *[black] Black
} won
end-reason-draw = Both sides' last pieces fell together
end-reason-far-edge = { $side } reached the far edge
end-reason-quick = { $side } won the round
end-reason-resignation = { $side } won by resignation
end-reason-timeouts = { $side } won: the other side ran out of time three times
end-reason-abandoned = { $side } won: the other side left
close = Close

## The match screen

play-seat-waiting = (waiting)
play-rematch-accept = Accept the rematch
play-rematch-offered = Rematch offered...
play-rematch-offer = Offer a rematch
play-notice-rematch = { $name } offers a rematch
play-notice-joined = { $name } joined
play-notice-left = { $name } lost the connection; the seat is kept for { $seconds } s
play-notice-back = { $name } is back
play-notice-timeout = { $name } ran out of time ({ $strikes } of 3)
play-notice-forfeited = { $name } forfeited
play-you-play = { $side ->
    [white] You play White
   *[black] You play Black
}
play-watching = Watching
play-heading = Chapaev
play-role-match = { $role } · match { $id }
play-back-to-lobby = Back to the lobby
play-name-you = { $name } (you)
play-round-shots = Round { $round } · { $shots ->
    [one] 1 shot
   *[other] { $shots } shots
}
play-round-shot = Round { $round } · shot { $shot }
play-pie-decides = Black decides: swap seats or not
play-waiting-friend = Waiting for your friend to join
play-shooting = shooting...
play-your-turn = Your turn: drag back from a piece
play-side-to-shoot = { $side ->
    [white] White
   *[black] Black
} to shoot
play-clock = clock { $time }
play-sound-on = Sound: on
play-sound-off = Sound: off
play-resign = Resign
play-resign-asking = Resign?
play-watch-replay = Watch the replay
play-resign-yes = Really resign
play-resign-no = Play on
play-pie-swap = Swap seats
play-pie-keep = Keep
play-invite-hint = Send your friend the link, or the id { $id }
play-copy-link = Copy invitation link
play-result = { $viewer ->
    [won] You won: { $how ->
        [far-edge] reached the far edge
        [quick] won the round
        [resignation] wins by resignation
        [timeouts] wins: the other side ran out of time three times
       *[abandoned] wins: the other side left
    }
    [lost] You lost: { $side } { $how ->
        [far-edge] reached the far edge
        [quick] won the round
        [resignation] wins by resignation
        [timeouts] wins: the other side ran out of time three times
       *[abandoned] wins: the other side left
    }
   *[watching] { $side } { $how ->
        [far-edge] reached the far edge
        [quick] won the round
        [resignation] wins by resignation
        [timeouts] wins: the other side ran out of time three times
       *[abandoned] wins: the other side left
    }
}
play-row-of = row { $row } of 8
play-chat-placeholder = say something...
play-chat-send = Send
page-loading = Loading Chapaev…
chat-line = { $name }: { $text }
chat-line-spectator = { $name } (watching): { $text }
chat-phrases = Phrases
chat-close = Close
chat-mute-opponent = Mute opponent
chat-unmute-opponent = Unmute opponent
chat-mute-players = Mute players
chat-unmute-players = Unmute players
chat-mute-spectators = Mute spectators
chat-unmute-spectators = Unmute spectators
phrase-hello = Hi!
phrase-good-luck = Good luck!
phrase-good-shot = Good shot!
phrase-oops = Oops!
phrase-well-played = Well played!
phrase-thanks = Thanks!
phrase-gg = gg
phrase-rematch = Rematch?
play-not-connected-retry = not connected; trying again
play-connecting-match = Connecting to the match...
play-link-open = connected
play-link-connecting = connecting...
play-link-retrying = reconnecting in { $seconds } s (try { $attempt })
play-link-failed = disconnected: { $why }
play-link-none = not connected
play-link-offline = offline match · not rated
play-link-offline-thinking = offline · the computer is thinking...
play-offline-id = offline
play-offline-not-kept = An offline match is not kept: no replay, no link.
play-link-copied = copied { $link }
play-leave-title = Leave the match?
play-leave-body = It goes on without you: come back within a minute or you forfeit it.
play-leave-no = Stay
play-leave-yes = Leave
play-invited-title = You are invited to a match
play-take-seat = Take the seat
play-just-watch = Just watch
play-seat-refused = Could not take the seat
play-watch-instead = Watch instead
play-slow-motion = Slow motion { $speed }x
play-skip-replay = Skip replay

## How to play

help-title = How to play Chapaev
help-close = Got it
rules-1 = Each side has eight checkers on its own row. White shoots first.
rules-2 = Your turn: press one of your checkers, drag back like a slingshot and let go.
rules-3 = The farther you pull, the harder the flick (see the arrow and the meter); drag back onto the checker to cancel.
rules-4 = A checker whose centre leaves the board is out.
rules-5 = Knock off enemy checkers without losing your own and you shoot again; otherwise the turn passes.
rules-6 = When only one colour is left the round is won: the winner's row moves a row closer to the other side and the winner starts the next round.
rules-7 = When the rows meet, the winner pushes the loser back. A row that reaches the far edge wins the match.
rules-8 = Each turn has a clock: run out and the turn passes; three times in a row and the match is lost.
rules-9 = A dropped connection keeps your seat: the game reconnects by itself.

## Accounts, players' pages and the leaderboard

loading = loading...
profile-facts = { $kind ->
    [bot] bot
   *[person] person
} · rating { $rating } ±{ $deviation } · { $games ->
    [one] 1 rated game
   *[other] { $games } rated games
}
profile-rating-over-time = Rating over time
profile-matches = Matches
profile-no-matches = no matches yet
account-creating = creating the account...
account-paste-key-first = paste the key exported from another browser
account-checking-key = checking the key...
account-new = A new account
account-name-placeholder = your name
account-create = Create
account-key-heading = Or a key from another browser
account-key-placeholder = paste the key
account-use-key = Use key
account-signed-in-as = Signed in as { $name }
account-rating = rating { $rating } · { $games ->
    [one] 1 rated game
   *[other] { $games } rated games
}
account-rating-unknown = rating —
account-my-page = My page
account-export-key = Export key
account-key-copied = the key is copied; keep it secret
account-your-key = Your key (paste it to sign in elsewhere):
account-title = Your account
account-name-hint = a name of { $min } to { $max } letters, digits, _ or -
account-name-rule = a name is { $min } to { $max } letters, digits, _ or -
leaderboard-people = People
leaderboard-bots = Bots
leaderboard-empty = no rated accounts yet
api-unexpected-answer = unexpected answer from the server: { $error }
api-unreachable = cannot reach the server ({ $error })
api-status = the server answered { $status }
api-unreadable-message = unreadable message from the server: { $error }

## Quick match

quick-sign-in-first = sign in to be paired with a stranger
quick-nobody-yet = Nobody yet? The adaptive computer plays at your level.
quick-next-person = You will play the next person who presses Quick match.
quick-starting = Starting...
quick-play-computer = Play the computer (adaptive)
quick-kind = { $kind ->
    [rated] rated
   *[casual] casual
}
quick-connecting = Connecting to the lobby ({ $kind }) · { $clock }
quick-looking = Looking for an opponent ({ $kind }) · { $clock }
quick-retrying = Connection lost; trying again · { $clock }
quick-found = Opponent found
quick-refused = No quick match: { $why }

## The board

board-your-turn = Your turn
board-release-to-cancel = release here to cancel

## Replay

replay-noise-verified = noise verified ({ $shots ->
    [one] 1 shot
   *[other] { $shots } shots
})
replay-noise-uncommitted = no noise commitment (an old record)
replay-noise-failed = noise NOT verified: { $code }
replay-cannot = cannot replay: { $error }
replay-result-drawn = drawn
replay-result-won = { $side ->
    [white] White
   *[black] Black
} won by { $how ->
    [far-edge] reaching the far edge
    [quick] winning the round
    [resignation] resignation
    [timeouts] the other side's timeouts
   *[abandoned] the other side's abandoning
}
replay-loading = Loading the record...
replay-head = Shot { $shot } of { $shots } · round { $round } · { $side ->
    [white] White
   *[black] Black
} plays { $piece } · White { $white } / Black { $black }
replay-no-shots = No shots were played
replay-title = Replay of { $id } · { $fairness }
replay-title-players = { $players } · { $fairness }
replay-previous-shot = Prev. shot
replay-next-shot = Next shot
replay-best-shots = Best shots
replay-best-shot = Shot { $shot } · { $off } off
replay-pause = Pause
replay-play = Play
replay-clock = { $at } / { $total } s

## The physics sandbox

file-downloaded = downloaded { $name }
file-saved = saved { $name }
file-save-failed = could not save { $name }: { $error }
sandbox-tool-select = Select
sandbox-tool-velocity = Velocity
sandbox-tool-disc = Disc
sandbox-tool-point = Point
sandbox-tool-line = Line
sandbox-tool-ray = Ray
sandbox-tool-segment = Segment
sandbox-tool-delete = Delete
sandbox-edge = Edge
sandbox-wall = Wall
sandbox-panel = Panel
# The tight layout's button that opens the tools and the speeds.
sandbox-menu = Menu
sandbox-export = Export
sandbox-import = Import
sandbox-exported = { $done } (the scene at t = { $t } s)
sandbox-new-discs = New discs
sandbox-radius = radius { $value }
sandbox-mass = mass { $value }
sandbox-presets = Presets
sandbox-galperin = Galperin n={ $n }
sandbox-brownian = Brownian box
sandbox-break = Chapaev break
sandbox-empty = Empty table
sandbox-fit = Fit view
sandbox-world = World
sandbox-gravity = g = { $g } m/s2
sandbox-body = Body { $id }
sandbox-body-at = at ({ $x }, { $y })  |v| { $v } m/s
sandbox-stop-it = Stop it
sandbox-body-absent = not in the scene at this time
sandbox-selection = Selection
sandbox-help-1 = Click a body to select it.
sandbox-help-2 = Drag it to move it; right-drag (or the Velocity tool) to aim it.
sandbox-help-3 = Wheel: zoom.  Drag empty: pan.
sandbox-help-4 = Space: play/pause.  Del: delete.
sandbox-time = t = { $t } s
sandbox-preset-failed = preset failed: { $error }
sandbox-imported = imported a scene of { $bodies ->
    [one] 1 body
   *[other] { $bodies } bodies
}
sandbox-import-refused = import refused, scene unchanged: { $error }
sandbox-refused = refused: { $error }
sandbox-lines-are-edges = new lines are edges: a disc whose centre crosses one falls off
sandbox-lines-are-walls = new lines are walls: discs bounce off them
sandbox-choose-file = choose a scene file (JSON)
sandbox-hint-galperin = Galperin's billiard: press Play (try 0.1x or 0.01x) and count the collisions
sandbox-hint-brownian = a heavy disc among light ones: press Play and watch its trail
sandbox-hint-break = the Chapaev break: press Play, or aim a checker with the right button
sandbox-hint-empty = place discs, points and lines with the tools above
stats-end-rest = end (rest)
stats-end-free = end (free)
stats-seconds = { $t } s
stats-time = time
stats-speed = speed
stats-computed-to = computed to
stats-events = events
stats-body-body = body-body
stats-body-line = body-line
stats-body-point = body-point
stats-stops = stops
stats-fell-off = fell off
stats-edits = edits
stats-bodies = bodies
stats-lines-points = lines, points
stats-frame = frame
stats-ms = { $ms } ms
stats-computing = computing
stats-ms-per-frame = { $ms } ms/frame
galperin-collisions = collisions
galperin-pi = pi to { $n } digits: { $pi }
galperin-ratio = mass ratio 100^{ $power }
galperin-done = all done
sandbox-speed = { $v } m/s
sandbox-grid = grid { $step } m
chart-no-games = no rated games yet
