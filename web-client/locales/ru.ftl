# «Чапаев онлайн»: интерфейс по-русски.
# У каждого сообщения здесь есть двойник с тем же id в en.ftl (это
# проверяет модульный тест). Числа идут через селекторы: одна шашка,
# две шашки, пять шашек.

## Общие слова

app-title = Чапаев онлайн
player-default-name = Игрок
sign-in = Войти
sign-out = Выйти
cancel = Отмена
join = Играть
watch = Смотреть
replay = Повтор
lobby = Главная
leaderboard = Рейтинг
how-to-play = Как играть
rules-short = Правила
copy-key = Скопировать ключ
key-copied = Ключ скопирован: сохраните его
signed-out-because = вы вышли: { $reason }
side-white = Белые
side-black = Чёрные
level-easy = лёгкий
level-medium = средний
level-hard = сильный
level-adaptive = адаптивный
computer-level = компьютер ({ $level })
shots-count = { $count ->
    [one] { $count } щелчок
    [few] { $count } щелчка
   *[many] { $count } щелчков
}
rounds-count = { $count ->
    [one] { $count } раунд
    [few] { $count } раунда
   *[many] { $count } раундов
}
games-count = { $count ->
    [one] { $count } партия
    [few] { $count } партии
   *[many] { $count } партий
}

## Главная

lobby-your-name = Ваше имя
lobby-signed-in = Вы вошли
lobby-rated-on = Рейтинг: да
lobby-rated-off = Рейтинг: нет
lobby-return-title = Ваша партия ещё идёт
lobby-return-body = Вы ушли посреди игры: вернитесь, пока вам не засчитали поражение.
lobby-return-yes = Вернуться
lobby-return-no = Остаться
lobby-sign-out-title = Выйти?
lobby-sign-out-body = Ключ — единственный способ вернуться в этот аккаунт. Сначала скопируйте его и сохраните в надёжном месте, иначе аккаунт пропадёт.
lobby-tagline = щёлкайте по своим шашкам, сбивайте чужие с доски
lobby-tagline-short = щёлкайте по своим, сбивайте чужие
lobby-quick-match = Быстрая игра
lobby-computer-easy = Компьютер: лёгкий
lobby-computer-medium = Компьютер: средний
lobby-computer-hard = Компьютер: сильный
lobby-computer-adaptive = Компьютер: адаптивный
lobby-friend = С другом (ссылка)
lobby-sandbox = Физическая песочница
lobby-offline = С компьютером без сети
lobby-offline-title = Игра с компьютером без сети
lobby-offline-body = Партия в этой странице, без сервера: без рейтинга, не сохраняется. Выберите уровень компьютера.
lobby-server-unreachable = Нет сервера: игра с компьютером без сети.
lobby-join-by-id = Войти по id
lobby-match-id = id партии
lobby-footer-short = Пишете бота? См. /api
lobby-footer = Пишете бота? Протокол HTTP и WebSocket описан на /api
lobby-none-yet = пока нет
lobby-list-open = Ждут соперника
lobby-list-live = Идут сейчас
lobby-list-finished = Сыгранные
lobby-creating = создаём партию...
lobby-fact-rated = рейтинговая
lobby-fact-not-playable = здесь не сыграть
lobby-fact-white-won = победили белые
lobby-fact-black-won = победили чёрные
lobby-fact-drawn = ничья
lobby-fact-waiting = ждёт
lobby-versus = { $first } — { $second }

## Журнал щелчков

shot-who-you = Вы
shot-nothing = { $who }: ничего не упало
shot-knocked = { $who } сбили { $taken ->
    [one] { $taken } шашку
    [few] { $taken } шашки
   *[many] { $taken } шашек
}
shot-lost = { $who } потеряли { $lost ->
    [one] { $lost } шашку
    [few] { $lost } шашки
   *[many] { $lost } шашек
}
shot-knocked-lost = { $who } сбили { $taken ->
    [one] { $taken } шашку
    [few] { $taken } шашки
   *[many] { $taken } шашек
}, потеряли { $lost }
shot-then-match-over = партия окончена
shot-then-you-won-round = вы выиграли раунд
shot-then-side-won-round = { $side ->
    [white] белые
   *[black] чёрные
} выиграли раунд
shot-then-round-drawn = раунд сыгран вничью
shot-then-you-again = бейте ещё раз
shot-then-again = бьют ещё раз
score-rounds-won = Раунды: белые { $white } · чёрные { $black }
score-rounds-drawn = вничью { $drawn }

## Конец партии

end-drawn = Ничья
end-you-won = Вы победили!
end-you-lost = Вы проиграли
end-side-won = { $side ->
    [white] Победили белые
   *[black] Победили чёрные
}
end-reason-draw = Последние шашки обеих сторон упали одновременно
end-reason-far-edge = { $side } дошли до дальнего края
end-reason-quick = { $side } выиграли раунд
end-reason-resignation = { $side } победили: соперник сдался
end-reason-timeouts = { $side } победили: соперник трижды не уложился во время
end-reason-abandoned = { $side } победили: соперник ушёл
close = Закрыть

## Партия

play-seat-waiting = (ждём)
play-rematch-accept = Принять реванш
play-rematch-offered = Реванш предложен...
play-rematch-offer = Предложить реванш
play-notice-rematch = { $name } предлагает реванш
play-notice-joined = { $name } за доской
play-notice-left = { $name }: связь потеряна; место держим { $seconds } с
play-notice-back = { $name } снова здесь
play-notice-timeout = { $name }: время вышло ({ $strikes } из 3)
play-notice-forfeited = { $name }: техническое поражение
play-you-play = { $side ->
    [white] Вы играете белыми
   *[black] Вы играете чёрными
}
play-watching = Вы зритель
play-heading = Чапаев
play-role-match = { $role } · партия { $id }
play-back-to-lobby = На главную
play-name-you = { $name } (вы)
play-round-shots = Раунд { $round } · { $shots ->
    [one] { $shots } щелчок
    [few] { $shots } щелчка
   *[many] { $shots } щелчков
}
play-round-shot = Раунд { $round } · щелчок { $shot }
play-pie-decides = Чёрные решают: меняться местами или нет
play-waiting-friend = Ждём, когда придёт ваш друг
play-shooting = щелчок...
play-your-turn = Ваш ход: оттяните свою шашку
play-side-to-shoot = { $side ->
    [white] Ход белых
   *[black] Ход чёрных
}
play-clock = часы { $time }
play-sound-on = Звук: вкл
play-sound-off = Звук: выкл
play-resign = Сдаться
play-resign-asking = Сдаться?
play-watch-replay = Смотреть повтор
play-resign-yes = Да, сдаюсь
play-resign-no = Играть дальше
play-pie-swap = Поменяться
play-pie-keep = Оставить
play-invite-hint = Пошлите другу ссылку или id { $id }
play-copy-link = Копировать ссылку
play-result = { $viewer ->
    [won] Вы победили: { $how ->
        [far-edge] дошли до дальнего края
        [quick] выиграли раунд
        [resignation] соперник сдался
        [timeouts] соперник трижды не уложился во время
       *[abandoned] соперник ушёл
    }
    [lost] Вы проиграли: { $how ->
        [far-edge] соперник дошёл до края
        [quick] соперник выиграл раунд
        [resignation] вы сдались
        [timeouts] время вышло трижды
       *[abandoned] вы ушли
    }
   *[watching] { $side } { $how ->
        [far-edge] дошли до дальнего края
        [quick] выиграли раунд
        [resignation] победили: соперник сдался
        [timeouts] победили: соперник трижды не уложился во время
       *[abandoned] победили: соперник ушёл
    }
}
play-row-of = ряд { $row } из 8
play-chat-placeholder = сообщение...
play-chat-send = Отправить
page-loading = Загружается «Чапаев»…
chat-line = { $name }: { $text }
chat-line-spectator = { $name } (зритель): { $text }
chat-phrases = Фразы
chat-close = Закрыть
chat-mute-opponent = Заглушить соперника
chat-unmute-opponent = Слушать соперника
chat-mute-players = Заглушить игроков
chat-unmute-players = Слушать игроков
chat-mute-spectators = Заглушить зрителей
chat-unmute-spectators = Слушать зрителей
phrase-hello = Привет!
phrase-good-luck = Удачи!
phrase-good-shot = Отличный щелчок!
phrase-oops = Ой!
phrase-well-played = Хорошо сыграно!
phrase-thanks = Спасибо!
phrase-gg = хорошая игра
phrase-rematch = Реванш?
play-not-connected-retry = нет связи; пробуем ещё
play-connecting-match = Подключаемся к партии...
play-link-open = на связи
play-link-connecting = подключаемся...
play-link-retrying = переподключение через { $seconds } с (попытка { $attempt })
play-link-failed = связь потеряна: { $why }
play-link-none = нет связи
play-link-offline = партия без сети · без рейтинга
play-link-offline-thinking = без сети · компьютер думает...
play-offline-id = без сети
play-offline-not-kept = Партия без сети не сохраняется: ни повтора, ни ссылки.
play-link-copied = скопировано: { $link }
play-leave-title = Уйти из партии?
play-leave-body = Партия идёт и без вас: вернитесь в течение минуты, иначе поражение.
play-leave-no = Остаться
play-leave-yes = Уйти
play-invited-title = Вас приглашают сыграть
play-take-seat = Сесть за доску
play-just-watch = Просто смотреть
play-seat-refused = Не удалось сесть за доску
play-watch-instead = Смотреть
play-slow-motion = Замедление { $speed }x
play-skip-replay = Пропустить

## Как играть

help-title = Как играть в Чапаева
help-close = Понятно
rules-1 = У каждой стороны восемь шашек в своём ряду. Первыми бьют белые.
rules-2 = Ваш ход: нажмите на свою шашку, оттяните её, как из рогатки, и отпустите.
rules-3 = Чем дальше оттянуть, тем сильнее щелчок (видно по стрелке и шкале); чтобы отменить, верните шашку на место.
rules-4 = Шашка, центр которой ушёл за край доски, выбывает.
rules-5 = Сбили чужие шашки и не потеряли своих — бьёте ещё раз; иначе ход переходит к сопернику.
rules-6 = Когда на доске остаются шашки одного цвета, раунд выигран: ряд победителя сдвигается на ряд ближе к сопернику, и победитель начинает следующий раунд.
rules-7 = Когда ряды встречаются, победитель оттесняет проигравшего. Ряд, дошедший до дальнего края, выигрывает партию.
rules-8 = На каждый ход даётся время: не успели — ход переходит; три раза подряд — партия проиграна.
rules-9 = При обрыве связи место за вами: игра переподключится сама.

## Аккаунты, страницы игроков и рейтинг

loading = загрузка...
profile-facts = { $kind ->
    [bot] бот
   *[person] человек
} · рейтинг { $rating } ±{ $deviation } · { $games ->
    [one] { $games } рейтинговая партия
    [few] { $games } рейтинговые партии
   *[many] { $games } рейтинговых партий
}
profile-rating-over-time = Рейтинг по времени
profile-matches = Партии
profile-no-matches = партий пока нет
account-creating = создаём аккаунт...
account-paste-key-first = вставьте ключ, сохранённый в другом браузере
account-checking-key = проверяем ключ...
account-new = Новый аккаунт
account-name-placeholder = ваше имя
account-create = Создать
account-key-heading = Или ключ из другого браузера
account-key-placeholder = вставьте ключ
account-use-key = Войти
account-signed-in-as = Вы вошли как { $name }
account-rating = рейтинг { $rating } · { $games ->
    [one] { $games } рейтинговая партия
    [few] { $games } рейтинговые партии
   *[many] { $games } рейтинговых партий
}
account-rating-unknown = рейтинг —
account-my-page = Моя страница
account-export-key = Сохранить ключ
account-key-copied = ключ скопирован; никому его не показывайте
account-your-key = Ваш ключ (вставьте его, чтобы войти в другом месте):
account-title = Ваш аккаунт
account-name-hint = имя: от { $min } до { $max } латинских букв, цифр, _ или -
account-name-rule = имя — это от { $min } до { $max } латинских букв, цифр, _ или -
leaderboard-people = Люди
leaderboard-bots = Боты
leaderboard-empty = рейтинговых аккаунтов пока нет
api-unexpected-answer = непонятный ответ сервера: { $error }
api-unreachable = сервер недоступен ({ $error })
api-status = сервер ответил { $status }
api-unreadable-message = непонятное сообщение сервера: { $error }

## Быстрая игра

quick-sign-in-first = войдите, чтобы играть с незнакомцем
quick-nobody-yet = Пока никого? Адаптивный компьютер играет на вашем уровне.
quick-next-person = Вы сыграете с тем, кто следующим нажмёт «Быстрая игра».
quick-starting = Начинаем...
quick-play-computer = С компьютером (адаптивный)
quick-kind = { $kind ->
    [rated] на рейтинг
   *[casual] без рейтинга
}
quick-connecting = Подключаемся ({ $kind }) · { $clock }
quick-looking = Ищем соперника ({ $kind }) · { $clock }
quick-retrying = Связь потеряна; пробуем снова · { $clock }
quick-found = Соперник найден
quick-refused = Быстрой игры не будет: { $why }

## Доска

board-your-turn = Ваш ход
board-release-to-cancel = отпустите здесь, чтобы отменить

## Повтор

replay-noise-verified = шум проверен ({ $shots ->
    [one] { $shots } щелчок
    [few] { $shots } щелчка
   *[many] { $shots } щелчков
})
replay-noise-uncommitted = шум не заверен (старая запись)
replay-noise-failed = шум НЕ подтверждён: { $code }
replay-cannot = повтор невозможен: { $error }
replay-result-drawn = ничья
replay-result-won = { $side ->
    [white] Белые
   *[black] Чёрные
} победили: { $how ->
    [far-edge] дошли до дальнего края
    [quick] выиграли раунд
    [resignation] соперник сдался
    [timeouts] соперник не уложился во время
   *[abandoned] соперник ушёл
}
replay-loading = Загружаем запись...
replay-head = Щелчок { $shot } из { $shots } · раунд { $round } · { $side ->
    [white] белые
   *[black] чёрные
} бьют шашкой { $piece } · белых { $white } / чёрных { $black }
replay-no-shots = Не было ни одного щелчка
replay-title = Повтор партии { $id } · { $fairness }
replay-title-players = { $players } · { $fairness }
replay-previous-shot = Пред. щелчок
replay-next-shot = След. щелчок
replay-best-shots = Лучшие щелчки
replay-best-shot = Щелчок { $shot } · сбито { $off }
replay-pause = Пауза
replay-play = Пуск
replay-clock = { $at } / { $total } с

## Физическая песочница

file-downloaded = скачан { $name }
file-saved = сохранён { $name }
file-save-failed = не удалось сохранить { $name }: { $error }
sandbox-tool-select = Выбор
sandbox-tool-velocity = Скорость
sandbox-tool-disc = Диск
sandbox-tool-point = Точка
sandbox-tool-line = Прямая
sandbox-tool-ray = Луч
sandbox-tool-segment = Отрезок
sandbox-tool-delete = Удалить
sandbox-edge = Край
sandbox-wall = Стена
sandbox-panel = Панель
sandbox-menu = Меню
sandbox-export = Экспорт
sandbox-import = Импорт
sandbox-exported = { $done } (сцена в момент t = { $t } с)
sandbox-new-discs = Новые диски
sandbox-radius = радиус { $value }
sandbox-mass = масса { $value }
sandbox-presets = Готовые сцены
sandbox-galperin = Гальперин n={ $n }
sandbox-brownian = Броуновский ящик
sandbox-break = Чапаевский разбой
sandbox-empty = Пустой стол
sandbox-fit = Показать всё
sandbox-world = Мир
sandbox-gravity = g = { $g } м/с²
sandbox-body = Тело { $id }
sandbox-body-at = в ({ $x }, { $y })  |v| { $v } м/с
sandbox-stop-it = Остановить
sandbox-body-absent = в этот момент его нет в сцене
sandbox-selection = Выделение
sandbox-help-1 = Щёлкните по телу, чтобы выбрать его.
sandbox-help-2 = Тащите, чтобы передвинуть; правой кнопкой (или инструментом «Скорость») задайте скорость.
sandbox-help-3 = Колесо: масштаб.  Тащите пустое место: сдвиг.
sandbox-help-4 = Пробел: пуск/пауза.  Del: удалить.
sandbox-time = t = { $t } с
sandbox-preset-failed = сцена не загрузилась: { $error }
sandbox-imported = загружена сцена: { $bodies ->
    [one] { $bodies } тело
    [few] { $bodies } тела
   *[many] { $bodies } тел
}
sandbox-import-refused = импорт отклонён, сцена не изменилась: { $error }
sandbox-refused = отклонено: { $error }
sandbox-lines-are-edges = новые линии — края: диск, чей центр пересёк линию, падает
sandbox-lines-are-walls = новые линии — стены: диски от них отскакивают
sandbox-choose-file = выберите файл сцены (JSON)
sandbox-hint-galperin = Бильярд Гальперина: нажмите «Пуск» (попробуйте 0.1x или 0.01x) и считайте соударения
sandbox-hint-brownian = тяжёлый диск среди лёгких: нажмите «Пуск» и следите за его следом
sandbox-hint-break = чапаевский разбой: нажмите «Пуск» или прицельтесь шашкой правой кнопкой
sandbox-hint-empty = расставьте диски, точки и линии инструментами сверху
stats-end-rest = конец (покой)
stats-end-free = конец (разлёт)
stats-seconds = { $t } с
stats-time = время
stats-speed = скорость
stats-computed-to = счёт до
stats-events = события
stats-body-body = диск–диск
stats-body-line = диск–линия
stats-body-point = диск–точка
stats-stops = остановки
stats-fell-off = упали
stats-edits = правки
stats-bodies = тела
stats-lines-points = линии, точки
stats-frame = кадр
stats-ms = { $ms } мс
stats-computing = считаем
stats-ms-per-frame = { $ms } мс/кадр
galperin-collisions = соударения
galperin-pi = пи до { $n } знаков: { $pi }
galperin-ratio = отношение масс 100^{ $power }
galperin-done = готово
sandbox-speed = { $v } м/с
sandbox-grid = сетка { $step } м
chart-no-games = рейтинговых партий пока нет
